#include "apps/part_list.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>

#include "core/errors.hpp"

namespace bemshape::apps {
namespace {

namespace fs = std::filesystem;

/// The extensions geometry::read_triangle_soup reads (geometry/mesh_io.hpp).
bool is_mesh_file(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".stl" || ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".3mf";
}

bool is_hidden(const fs::path& path) {
  const std::string name = path.filename().string();
  return !name.empty() && name.front() == '.';
}

/// The mesh files under `folder`, in path order.
std::vector<std::string> mesh_files_under(const std::string& folder) {
  std::vector<std::string> files;
  std::error_code error;
  fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, error);
  if (error)
    throw InputError(folder + ": cannot list the folder: " + error.message());
  for (; it != fs::recursive_directory_iterator(); it.increment(error)) {
    if (error)
      throw InputError(folder + ": cannot list the folder: " + error.message());
    if (is_hidden(it->path())) {
      if (it->is_directory())
        it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file() && is_mesh_file(it->path()))
      files.push_back(it->path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty())
    throw InputError(folder + ": the folder holds no mesh file (.stl, .obj, .off, .ply, .3mf)");
  return files;
}

std::string trimmed(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  if (first == std::string::npos)
    return "";
  return line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
}

fs::path absolute_path(const std::string& path) {
  return fs::absolute(fs::path(path)).lexically_normal();
}

}  // namespace

std::vector<Part> list_parts(const std::vector<std::string>& inputs,
                             const std::vector<std::string>& lists,
                             const std::filesystem::path& reports) {
  std::vector<std::string> named = inputs;
  for (const std::string& list : lists) {
    std::ifstream in(list);
    if (!in)
      throw InputError(list + ": cannot read the list of parts (--list)");
    std::string line;
    while (std::getline(in, line)) {
      const std::string entry = trimmed(line);
      if (!entry.empty() && entry.front() != '#')
        named.push_back(entry);
    }
  }
  std::vector<std::string> paths;
  for (const std::string& input : named) {
    if (fs::is_directory(input)) {
      const std::vector<std::string> files = mesh_files_under(input);
      paths.insert(paths.end(), files.begin(), files.end());
    } else {
      paths.push_back(input);
    }
  }
  std::vector<Part> parts;
  std::vector<fs::path> absolute;
  std::set<fs::path> seen;
  for (const std::string& path : paths) {
    const fs::path a = absolute_path(path);
    if (!seen.insert(a).second)
      continue;
    parts.push_back({path, {}});
    absolute.push_back(a);
  }
  if (parts.empty())
    throw InputError("no parts to check: name mesh files, folders or a --list file");
  // The folder every part is under: the common leading components of their folders.
  fs::path common = absolute.front().parent_path();
  for (const fs::path& a : absolute) {
    const fs::path folder = a.parent_path();
    fs::path shared;
    auto c = common.begin();
    for (auto p = folder.begin(); c != common.end() && p != folder.end() && *c == *p; ++c, ++p)
      shared /= *c;
    common = shared;
  }
  for (std::size_t i = 0; i < parts.size(); ++i)
    parts[i].report = reports / (absolute[i].lexically_relative(common).string() + ".json");
  return parts;
}

}  // namespace bemshape::apps
