// Runs the real `bemshape` executable (path compiled in as BEMSHAPE_EXECUTABLE) on the
// bad-input corpus and the sample meshes, checking exit codes, the first line of stderr and
// run time.
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/apps/bemshape_runner.hpp"
#include "tests/support/time_bound.hpp"

namespace fs = std::filesystem;
using namespace bemshape::testing;

namespace {

const std::string data = BEMSHAPE_TEST_DATA_DIR;

Run check(const std::string& file) {
  return run_bemshape("check '" + file + "'");
}

/// Refused input: exit 2, first stderr line names the file and the problem, under a second.
void expect_refused(const std::string& file, const std::string& problem) {
  CAPTURE(file);
  const Run r = check(file);
  CAPTURE(r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.first_error_line(), Catch::StartsWith("bemshape: error: " + file + ": "));
  CHECK_THAT(r.first_error_line(), Catch::Contains(problem));
  CHECK(r.seconds < bemshape::test::time_bound(1.0));
}

/// Repaired input: exit 0, usable, the repair named in the report, under a second.
void expect_repaired(const std::string& file, const std::string& repair) {
  CAPTURE(file);
  const Run r = check(file);
  CAPTURE(r.out, r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK_THAT(r.out, Catch::Contains(repair));
  CHECK_THAT(r.out, Catch::Contains("result: usable"));
  CHECK(r.seconds < bemshape::test::time_bound(1.0));
}

}  // namespace

TEST_CASE("unreadable and malformed files are refused with one clear line") {
  const std::string bad = data + "/bad/";
  expect_refused(bad + "empty.stl", "the file is empty");
  expect_refused(bad + "whitespace_only.stl", "only white space");
  expect_refused(bad + "not_a_mesh.stl", "not an ASCII STL");
  expect_refused(bad + "truncated_binary.stl", "truncated");
  expect_refused(bad + "truncated_ascii.stl", "truncated");
  expect_refused(bad + "count_mismatch.stl", "header announces 100 triangles");
  expect_refused(bad + "claims_4e9_triangles.stl", "header announces 4000000000 triangles");
  expect_refused(bad + "garbage_numbers.stl", "'zero' is not a number");
  expect_refused(bad + "nan_coordinate.stl", "'nan' is not finite");
  expect_refused(bad + "inf_coordinate_binary.stl", "non-finite coordinate");
  expect_refused(bad + "bad_index.obj", "refers to vertex number 99");
  expect_refused(bad + "cube.xyz", "unsupported file extension");
  expect_refused(bad + "not_a_zip.3mf", "cannot be read as a 3MF package: Could not read ZIP");
  expect_refused(bad + "bad_index.3mf", "Invalid model node index");
  expect_refused(data + "/does_not_exist.stl", "no such file");
  expect_refused(data + "/bad", "is a directory");
}

TEST_CASE("meshes that do not bound a solid are refused, saying what, how many and where") {
  const std::string bad = data + "/bad/";
  expect_refused(bad + "single_triangle.stl", "3 open boundary edges (first at ");
  expect_refused(bad + "open_box.stl", "4 open boundary edges (first at ");
  expect_refused(data + "/meshes/teapot.stl", "64 open boundary edges");
  const Run r = check(bad + "open_box.stl");
  CHECK_THAT(r.first_error_line(),
             Catch::Contains("1 hole up to 1.41 across, larger than the repair length 0.0346 "
                             "(2 % of the bounding-box diagonal)") &&
                 Catch::Contains("close the holes"));
  CHECK_THAT(r.out, Catch::Contains("result: refused"));
}

TEST_CASE("repairable defects are repaired and reported, exit 0") {
  const std::string bad = data + "/bad/";
  expect_repaired(bad + "inverted_normals.stl", "reversed 12 faces so that every shell bounds");
  expect_repaired(bad + "inconsistent_orientation.stl", "made consistent by reversing 3 faces");
  expect_repaired(bad + "duplicate_face.stl", "1 duplicate face");
  expect_repaired(bad + "zero_area_face.obj", "1 zero-area face");
  expect_repaired(bad + "quads.obj", "split 6 polygons with more than 3 corners into 12 triangles");
  expect_repaired(bad + "cubes_sharing_edge.stl",
                  "split 1 non-manifold edge (first at 1, 1, 0.5) by pairing the faces");
  expect_repaired(bad + "cubes_sharing_vertex.stl", "duplicated 1 vertex shared by separate fans");
  expect_repaired(bad + "self_intersecting.stl", "united 2 overlapping bodies");
  expect_repaired(bad + "small_hole.stl", "filled a hole of 3 edges, 0.0141 across, at (");
  expect_repaired(bad + "pushed_through.stl", "cut out 6 faces with 6 intersecting pairs");
  // The union of two unit cubes overlapping in a cube of side 1/2: 2 − 1/8.
  CHECK_THAT(check(bad + "self_intersecting.stl").out, Catch::Contains("volume          1.875"));
}

TEST_CASE("an input that cannot be read is refused: a FIFO always, a chmod 000 file unless root") {
  // A FIFO needs no permissions, so this part runs as root too; the reader must refuse it
  // without opening it for a blocking read (the check would hang until killed).
  const fs::path fifo = fs::temp_directory_path() /
                        ("bemshape_test_fifo_" + std::to_string(::getpid()) + ".stl");
  fs::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  expect_refused(fifo.string(), "is a FIFO (named pipe), not a regular mesh file");
  fs::remove(fifo);

  const fs::path file = fs::temp_directory_path() / "bemshape_test_unreadable.stl";
  fs::copy_file(data + "/formats/cube_binary.stl", file, fs::copy_options::overwrite_existing);
  fs::permissions(file, fs::perms::none);
  if (::geteuid() != 0)  // chmod 000 does not stop root from reading
    expect_refused(file.string(), "cannot be opened for reading");
  fs::permissions(file, fs::perms::owner_all);
  fs::remove(file);
}

TEST_CASE("check on a good mesh prints the report, --report writes it as JSON") {
  const fs::path json = fs::temp_directory_path() / "bemshape_test_report.json";
  const Run r = run_bemshape("check '" + data + "/meshes/plate_holes.STL' --report '" + json.string() + "'");
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  for (const char* line : {"faces", "vertices", "shells", "cavities", "volume", "area",
                           "bounding box", "result: usable"})
    CHECK_THAT(r.out, Catch::Contains(line));
  const nlohmann::json report = nlohmann::json::parse(slurp(json));
  fs::remove(json);
  CHECK(report["usable"] == true);
  CHECK(report["faces"] == 1252);
  CHECK(report["shells"] == 1);
  const double dz = report["bounding_box"]["max"][2].get<double>() -
                    report["bounding_box"]["min"][2].get<double>();
  CHECK(dz == Approx(12.7).epsilon(1e-6));
}

TEST_CASE("usage: --help and --version exit 0, bad usage exits 2") {
  const Run help = run_bemshape("--help");
  CHECK(help.exit_code == 0);
  CHECK_THAT(help.out, Catch::Contains("check"));
  const Run check_help = run_bemshape("check --help");
  CHECK(check_help.exit_code == 0);
  CHECK_THAT(check_help.out, Catch::Contains("units"));
  CHECK_THAT(check_help.out, Catch::Contains("--weld-tolerance"));
  const Run version = run_bemshape("--version");
  CHECK(version.exit_code == 0);
  CHECK_THAT(version.out, Catch::Contains("bemshape ") && Catch::Contains("-march="));
  for (const char* args : {"", "check", "frobnicate", "check a.stl --no-such-option",
                           "check a.stl --weld-tolerance -1"}) {
    CAPTURE(args);
    const Run r = run_bemshape(args);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.first_error_line(), Catch::StartsWith("bemshape: error: "));
  }
}
