// bemshape's own OBJ, OFF and PLY readers (geometry/detail/polygon_file_readers.hpp),
// through read_triangle_soup. The first case of each format is an input that fuzzing found
// to break OpenMesh's reader (fuzz/regressions/), which these readers replaced.
#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "core/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/vertex_welding.hpp"
#include "tests/support/time_bound.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

namespace {

namespace fs = std::filesystem;
const std::string data = BEMSHAPE_TEST_DATA_DIR;
const fs::path regressions = fs::path(BEMSHAPE_TEST_DATA_DIR) / "../../fuzz/regressions";

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Writes `bytes` to a temporary file with `extension` and returns its path. The name carries
/// the process id: ctest runs the test cases as parallel processes, which must not share a file.
fs::path write_file(const std::string& bytes, const std::string& extension) {
  const fs::path path = fs::temp_directory_path() /
                        ("bemshape_test_reader_" + std::to_string(::getpid()) + extension);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

TriangleSoup read_bytes(const std::string& bytes, const std::string& extension) {
  return read_triangle_soup(write_file(bytes, extension));
}

/// The InputError message for `bytes` read as a file with `extension`, without the path;
/// "no error" if the file is accepted.
std::string refusal(const std::string& bytes, const std::string& extension) {
  const fs::path path = write_file(bytes, extension);
  try {
    read_triangle_soup(path);
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string prefix = path.string() + ": ";
    REQUIRE(what.substr(0, prefix.size()) == prefix);
    return what.substr(prefix.size());
  }
  return "no error";
}

/// The unit cube as read from tests/data/formats/cube.obj: 8 vertices, 12 triangles.
void check_unit_cube(const TriangleSoup& soup) {
  REQUIRE(soup.faces.rows() == 12);
  CHECK(weld_vertices(soup.vertices, soup.faces).vertices.rows() == 8);
  const TriangleSoup reference = read_triangle_soup(data + "/formats/cube.obj");
  CHECK(soup.vertices == reference.vertices);
  CHECK(soup.faces == reference.faces);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The unit cube as binary PLY (float x y z; uchar count, int indices) in the given order.
std::string binary_ply_cube(bool big_endian) {
  const TriangleSoup cube = read_triangle_soup(data + "/formats/cube.obj");
  std::string out = std::string("ply\nformat ") +
                    (big_endian ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 12\n"
                    "property list uchar int vertex_indices\nend_header\n";
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  const auto put = [&](const auto value) {
    char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);
    if (swap)
      std::reverse(bytes, bytes + sizeof value);
    out.append(bytes, sizeof value);
  };
  for (Eigen::Index v = 0; v < 8; ++v)
    for (int k = 0; k < 3; ++k)
      put(static_cast<float>(cube.vertices(v, k)));
  for (Eigen::Index f = 0; f < 12; ++f) {
    put(static_cast<std::uint8_t>(3));
    for (int k = 0; k < 3; ++k)
      put(static_cast<std::int32_t>(cube.faces(f, k)));
  }
  return out;
}

}  // namespace

TEST_CASE("OBJ: the face line that aborted OpenMesh's reader is refused at its line") {
  // fuzz/regressions/fuzz_obj/openmesh_obj_reader_abort: line 4 is "f \0\0\0\0\0001 3 4 2";
  // OpenMesh's reader found no vertex in it and failed assert(!vhandles.empty()).
  const std::string bytes = file_bytes(regressions / "fuzz_obj/openmesh_obj_reader_abort");
  CHECK(refusal(bytes, ".obj") ==
        "line 4: '\\x00\\x00\\x00\\x00\\x001' is not a face corner (a vertex number counting "
        "from 1, or negative counting back from the last vertex, optionally followed by "
        "/texture/normal numbers)");
  CHECK(refusal("v 0 0 0\nv 1 0 0\nv 0 1 0\nf\n", ".obj") ==
        "line 4: a face line lists no vertices");
  CHECK(refusal("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", ".obj").find("line 4: '0' is not") == 0);
}

TEST_CASE("OBJ: corner references with texture and normal numbers, and relative ones") {
  const std::string vertices = file_bytes(data + "/formats/cube.obj");
  const std::string header = vertices.substr(0, vertices.find("\nf ") + 1);
  // The same 12 triangles: "v/vt/vn", "v//vn" and negative (relative) references.
  std::string faces;
  const TriangleSoup cube = read_triangle_soup(data + "/formats/cube.obj");
  for (Eigen::Index f = 0; f < 12; ++f) {
    const int a = cube.faces(f, 0) + 1, b = cube.faces(f, 1) + 1, c = cube.faces(f, 2) + 1;
    faces += "f " + std::to_string(a) + "/1/1 " + std::to_string(b) + "//2 " +
             std::to_string(c - 9) + "  # comment\n";
  }
  check_unit_cube(read_bytes(header + "vt 0 0\nvn 0 0 1\ng part\ns off\n" + faces, ".obj"));
  CHECK(refusal("v 0 0 0\nf -1 -2 1\n", ".obj") ==
        "line 2: a face refers to vertex -2 but only 1 vertices precede it: the file is corrupt");
  CHECK(refusal("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 40\nf 1 2 7\n", ".obj") ==
        "line 5: a face refers to vertex number 40 (counting from 1) but the file has only 3 "
        "vertices");
  CHECK(refusal("v 0 0 nan\n", ".obj") == "line 1: coordinate 'nan' is not finite");
}

TEST_CASE("OFF: the input that took OpenMesh's reader 27 s is refused at once") {
  // fuzz/regressions/fuzz_off/openmesh_off_reader_slow starts with "OFF*\xe8" and a count of
  // 10^22; OpenMesh's reader spent more than 10 s (libFuzzer's limit) in read_ascii.
  const std::string bytes = file_bytes(regressions / "fuzz_off/openmesh_off_reader_slow");
  const auto start = std::chrono::steady_clock::now();
  CHECK(refusal(bytes, ".off") ==
        "line 1: not an OFF file: it starts with 'OFF*\\xe89999999999999999999993', expected "
        "OFF (or COFF, NOFF, STOFF, ...)");
  // The same count after a correct keyword: no vertex lines follow, nothing is allocated.
  CHECK(refusal("OFF\n99999999999999999999 1 0\n", ".off") ==
        "line 2: OFF header: expected the vertex, face and edge counts (whole numbers)");
  CHECK(refusal("OFF\n4000000000 1 0\n0 0 0\n", ".off") ==
        "the OFF header (line 2) announces 4000000000 vertices and 1 faces but the file ends "
        "after 1 vertices: the file is truncated or corrupt");
  CHECK(seconds_since(start) < bemshape::test::time_bound(1.0));
}

TEST_CASE("OFF: variants, comments and per-face colours are read, malformed faces refused") {
  const TriangleSoup quads = read_triangle_soup(data + "/formats/cube_quads.off");
  // COFF: a colour after every vertex; a colour after a face; comments anywhere.
  std::string coff = "COFF # coloured\n8 12 0\n";
  const TriangleSoup cube = read_triangle_soup(data + "/formats/cube.obj");
  for (Eigen::Index v = 0; v < 8; ++v)
    coff += std::to_string(cube.vertices(v, 0)) + " " + std::to_string(cube.vertices(v, 1)) + " " +
            std::to_string(cube.vertices(v, 2)) + " 255 0 0 255\n";
  for (Eigen::Index f = 0; f < 12; ++f)
    coff += "3 " + std::to_string(cube.faces(f, 0)) + " " + std::to_string(cube.faces(f, 1)) + " " +
            std::to_string(cube.faces(f, 2)) + " 0.5 0.5 0.5\n";
  check_unit_cube(read_bytes(coff, ".off"));
  CHECK(quads.faces.rows() == 12);

  CHECK(refusal("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", ".off") ==
        "line 6: face 0 announces 4 corners but lists 3 numbers: the file is corrupt");
  CHECK(refusal("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ".off") ==
        "line 6: face 0 refers to vertex '3' but the file has 3 vertices (numbered from 0): "
        "the file is corrupt");
  CHECK(refusal("OFF BINARY\n", ".off") ==
        "line 1: binary OFF is not supported: export ASCII OFF, PLY or STL instead");
  CHECK(refusal("4OFF\n", ".off") ==
        "line 1: '4OFF': OFF files with 4-D or n-D vertices are not supported");
}

TEST_CASE("PLY: the header that crashed OpenMesh's can_u_read is refused at its line") {
  // fuzz/regressions/fuzz_ply/openmesh_ply_can_u_read_segv: line 3 reads "elemeelemet nface
  // 12" and no vertex element follows; OpenMesh's header parser dereferenced a missing one.
  const std::string bytes = file_bytes(regressions / "fuzz_ply/openmesh_ply_can_u_read_segv");
  CHECK(refusal(bytes, ".ply") == "line 3: unknown PLY header line starting with 'elemeelemet'");
  CHECK(refusal("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n3 0 1 2\n",
                ".ply") == "the PLY header declares no 'vertex' element");
  CHECK(refusal("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                "property float z\nend_header\n0 0 0\n",
                ".ply") ==
        "the PLY header declares no 'face' element: bemshape needs a surface mesh of triangles "
        "or polygons, not a point cloud");
  // fuzz/regressions/fuzz_ply/header_without_end_header: OpenMesh looped forever.
  CHECK(refusal("ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\n", ".ply") ==
        "the PLY header has no 'end_header' line: the file is truncated or corrupt");
}

TEST_CASE("PLY: binary little- and big-endian files read the same cube as ASCII") {
  check_unit_cube(read_triangle_soup(data + "/formats/cube.ply"));
  check_unit_cube(read_bytes(binary_ply_cube(false), ".ply"));
  check_unit_cube(read_bytes(binary_ply_cube(true), ".ply"));
  // Extra elements and properties (normals, a list of texture coordinates) are skipped.
  std::string extra = file_bytes(data + "/formats/cube.ply");
  const auto at = [&](const std::string& s) { return extra.find(s); };
  extra.insert(at("element face"), "property uchar red\n");
  extra.insert(at("end_header"),
               "property list uchar float texcoord\nelement edge 1\n"
               "property int vertex1\nproperty int vertex2\n");
  std::string body;
  std::size_t line_start = at("end_header\n") + 11;
  for (int v = 0; v < 8; ++v) {
    const std::size_t end = extra.find('\n', line_start);
    body += extra.substr(line_start, end - line_start) + " 200\n";
    line_start = end + 1;
  }
  for (int f = 0; f < 12; ++f) {
    const std::size_t end = extra.find('\n', line_start);
    body += extra.substr(line_start, end - line_start) + " 2 0.5 0.25\n";
    line_start = end + 1;
  }
  extra = extra.substr(0, at("end_header\n") + 11) + body + "0 1\n";
  check_unit_cube(read_bytes(extra, ".ply"));
}

TEST_CASE("PLY: counts larger than the data, truncated bodies and bad indices are refused") {
  const std::string ascii = file_bytes(data + "/formats/cube.ply");
  std::string claims = ascii;
  claims.replace(claims.find("vertex 8"), 8, "vertex 4000000000");
  const auto start = std::chrono::steady_clock::now();
  CHECK(refusal(claims, ".ply") ==
        "the PLY header announces elements that need at least 24000000024 bytes but only 192 "
        "follow it: the file is truncated or the header is corrupt");
  std::string binary = binary_ply_cube(false);
  std::string binary_claims = binary;
  binary_claims.replace(binary_claims.find("vertex 8"), 8, "vertex 4000000000");
  CHECK(refusal(binary_claims, ".ply") ==
        "the PLY header announces elements that need at least 48000000012 bytes but only 252 "
        "follow it: the file is truncated or the header is corrupt");
  CHECK(seconds_since(start) < bemshape::test::time_bound(1.0));

  // Enough bytes for the minimum, but the data ends inside the last face's list.
  const std::size_t body = binary.find("end_header\n") + 11;
  CHECK(refusal(binary.substr(0, binary.size() - 5), ".ply") ==
        "the PLY header announces 12 face elements but the data ends in number 11 (byte 414): "
        "the file is truncated or corrupt");
  std::string long_list = binary;
  long_list[body + 96 + 11 * 13] = 100;  // the last face claims 100 corners
  CHECK(refusal(long_list, ".ply") ==
        "the PLY header announces 12 face elements but the data ends in number 11 (byte 422): "
        "the file is truncated or corrupt");
  // A corrupt list length elsewhere shifts what follows: the bytes read as the third face's
  // indices are out of range.
  std::string corrupt = binary;
  corrupt[body + 96] = 4;  // the first face claims 4 corners
  CHECK(refusal(corrupt, ".ply") ==
        "face 2 refers to vertex 16777216 but the file has 8 vertices before it (byte 289): the "
        "file is corrupt");

  std::string bad_index = ascii;
  bad_index.replace(bad_index.find("3 0 2 3"), 7, "3 0 2 8");
  CHECK(refusal(bad_index, ".ply") ==
        "face 0 refers to vertex 8 but the file has 8 vertices before it (line 18): the file "
        "is corrupt");
  std::string nan = ascii;
  nan.replace(nan.find("1.0 1.0 1.0"), 3, "nan");
  CHECK(refusal(nan, ".ply") ==
        "vertex 7 has a non-finite coordinate (line 17): the file is corrupt");
  CHECK(refusal(ascii.substr(0, ascii.size() - 20), ".ply") ==
        "the PLY header announces 12 face elements but the data ends in number 9 (line 27): "
        "the file is truncated or corrupt");
}
