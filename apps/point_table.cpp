#include "apps/point_table.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace bemshape::apps {
namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  for (char c : line) {
    if (c == ',' || c == ';' || std::isspace(static_cast<unsigned char>(c))) {
      if (!field.empty() || c == ',' || c == ';')
        fields.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  if (!field.empty())
    fields.push_back(field);
  return fields;
}

bool parse_number(const std::string& text, double& value) {
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value);
  return result.ec == std::errc() && result.ptr == end && std::isfinite(value);
}

}  // namespace

Eigen::MatrixX3d read_points(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in)
    throw InputError(path.string() + ": cannot open the points file");
  std::vector<double> coordinates;
  int column[3] = {0, 1, 2};
  std::string line;
  std::size_t line_number = 0;
  bool first_data_line = true;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#')
      continue;
    const std::vector<std::string> fields = split_fields(line.substr(start));
    double value = 0.0;
    if (first_data_line && !fields.empty() && !parse_number(fields[0], value)) {
      // A header line: use the columns named x, y, z if present.
      for (int k = 0; k < 3; ++k)
        for (std::size_t c = 0; c < fields.size(); ++c)
          if (fields[c] == std::string(1, "xyz"[k]) || fields[c] == std::string(1, "XYZ"[k]))
            column[k] = static_cast<int>(c);
      first_data_line = false;
      continue;
    }
    first_data_line = false;
    for (int k = 0; k < 3; ++k) {
      const auto c = static_cast<std::size_t>(column[k]);
      if (c >= fields.size() || !parse_number(fields[c], value))
        throw InputError(path.string() + ":" + std::to_string(line_number) +
                         ": expected three finite coordinates x, y, z, got '" + line + "'");
      coordinates.push_back(value);
    }
  }
  if (coordinates.empty())
    throw InputError(path.string() + ": no points (expected lines 'x,y,z')");
  const auto n = static_cast<Eigen::Index>(coordinates.size() / 3);
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      coordinates.data(), n, 3);
}

}  // namespace bemshape::apps
