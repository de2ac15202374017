#pragma once
// Shared helpers of the end-to-end tests of the thickness and features commands: run the
// real `bemshape` executable (path compiled in as BEMSHAPE_EXECUTABLE), write generated
// solids as binary STL into a per-process temporary folder, and read back the CSV and JSON
// outputs.

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "apps/output/stl_writer.hpp"
#include "fem/binary_image.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::testing {

namespace fs = std::filesystem;

struct Run {
  int exit_code = -1;
  std::string out, err;
  double seconds = 0.0;
  std::string first_error_line() const { return err.substr(0, err.find('\n')); }
};

inline std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A folder for this test process's files, removed at exit.
inline const fs::path& scratch_folder() {
  struct Folder {
    fs::path path;
    Folder() {
      path = fs::temp_directory_path() / ("bemshape_apps_test_" + std::to_string(::getpid()));
      fs::create_directories(path);
    }
    ~Folder() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

inline std::string scratch(const std::string& name) {
  return (scratch_folder() / name).string();
}

/// Runs `bemshape <arguments>` (arguments already shell-quoted), capturing stdout and stderr;
/// `environment`: "NAME=value ..." set for this run only.
inline Run run_bemshape(const std::string& arguments, const std::string& environment = "") {
  const fs::path err_file = scratch_folder() / "stderr.txt";
  const std::string command = (environment.empty() ? "" : "env " + environment + " ") +
                              std::string("'") + BEMSHAPE_EXECUTABLE + "' " + arguments + " 2>'" +
                              err_file.string() + "'";
  Run r;
  const auto start = std::chrono::steady_clock::now();
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
    r.out.append(buffer, n);
  const int status = ::pclose(pipe);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  REQUIRE(WIFEXITED(status));
  r.exit_code = WEXITSTATUS(status);
  r.err = slurp(err_file);
  return r;
}

/// Writes `mesh` as binary STL to the scratch folder and returns the path.
inline std::string write_mesh(const geometry::SurfaceMesh& mesh, const std::string& name) {
  const std::string path = scratch(name);
  output::write_binary_stl(path, mesh.vertices(), mesh.faces());
  return path;
}

/// Writes a 40×40 PNG with an L-shaped solid (30×30 pixels, arms 10 wide) to the scratch
/// folder and returns the path: `bemshape fem` on it takes a fraction of a second and writes a
/// .vti of about 60 kB.
inline std::string write_l_shape_png(const std::string& name) {
  fem::BinaryImage<2> image;
  image.size = {40, 40};
  image.solid.assign(1600, 0);
  for (int y = 5; y < 35; ++y)
    for (int x = 5; x < 35; ++x)
      if (x < 15 || y < 15) image.solid[static_cast<std::size_t>(y * 40 + x)] = 1;
  const std::string png = scratch(name);
  fem::write_binary_png(png, image);
  return png;
}

/// A CSV file: its header and its rows as numbers.
struct CsvTable {
  std::vector<std::string> header;
  Eigen::MatrixXd rows;
  Eigen::Index column(const std::string& name) const {
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == name)
        return static_cast<Eigen::Index>(c);
    FAIL("no column " << name);
    return -1;
  }
  Eigen::VectorXd col(const std::string& name) const { return rows.col(column(name)); }
  std::string header_line() const {
    std::string line;
    for (std::size_t c = 0; c < header.size(); ++c)
      line += (c ? "," : "") + header[c];
    return line;
  }
};

/// Parses comma-separated text with one header line; every row must have the header's width.
inline CsvTable parse_csv(const std::string& text) {
  CsvTable table;
  std::istringstream in(text);
  std::string line;
  REQUIRE(std::getline(in, line));
  {
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ','))
      table.header.push_back(field);
  }
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string field;
    std::vector<double> row;
    while (std::getline(fields, field, ','))
      row.push_back(std::stod(field));
    REQUIRE(row.size() == table.header.size());
    rows.push_back(row);
  }
  table.rows.resize(static_cast<Eigen::Index>(rows.size()),
                    static_cast<Eigen::Index>(table.header.size()));
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < rows[r].size(); ++c)
      table.rows(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = rows[r][c];
  return table;
}

inline nlohmann::json read_json(const std::string& path) {
  return nlohmann::json::parse(slurp(path));
}

}  // namespace bemshape::testing
