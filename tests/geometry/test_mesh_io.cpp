#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <string>

#include "core/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/primitive_meshes.hpp"
#include "geometry/vertex_welding.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

namespace {

const std::string data = BEMSHAPE_TEST_DATA_DIR;

/// Signed volume (1/6) Σ a·(b×c) of a triangle soup.
double soup_volume(const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f) {
  double volume = 0.0;
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    volume += Eigen::Vector3d(v.row(f(i, 0)))
                  .dot(Eigen::Vector3d(v.row(f(i, 1))).cross(Eigen::Vector3d(v.row(f(i, 2)))));
  return volume / 6.0;
}

std::string message_of(const std::string& path) {
  try {
    read_triangle_soup(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("every supported format reads the unit cube") {
  for (const char* name :
       {"cube_ascii.stl", "cube_binary.stl", "cube.obj", "cube.ply", "cube_quads.off"}) {
    CAPTURE(name);
    const TriangleSoup soup = read_triangle_soup(data + "/formats/" + name);
    const WeldResult welded = weld_vertices(soup.vertices, soup.faces);
    CHECK(soup.faces.rows() == 12);
    CHECK(welded.vertices.rows() == 8);
    CHECK(soup_volume(soup.vertices, soup.faces) == Approx(1.0).epsilon(1e-12));
    CHECK(soup.vertices.minCoeff() == 0.0);
    CHECK(soup.vertices.maxCoeff() == 1.0);
  }
  CHECK(read_triangle_soup(data + "/formats/cube_ascii.stl").format == "ASCII STL");
  CHECK(read_triangle_soup(data + "/formats/cube_binary.stl").format == "binary STL");
}

TEST_CASE("quads are split into fans and reported") {
  const TriangleSoup soup = read_triangle_soup(data + "/formats/cube_quads.off");
  CHECK(soup.polygons_triangulated == 6);
  CHECK(soup.triangles_from_polygons == 12);
}

TEST_CASE("bundled meshes read with their documented sizes") {
  const TriangleSoup plate = read_triangle_soup(data + "/meshes/plate_holes.STL");
  CHECK(plate.faces.rows() == 1252);
  const Eigen::RowVector3d extent =
      plate.vertices.colwise().maxCoeff() - plate.vertices.colwise().minCoeff();
  CHECK(extent(0) == Approx(203.2).epsilon(1e-6));
  CHECK(extent(1) == Approx(304.8).epsilon(1e-6));
  CHECK(extent(2) == Approx(12.7).epsilon(1e-6));

  const TriangleSoup sphere = read_triangle_soup(data + "/meshes/unit_sphere.STL");
  CHECK(sphere.faces.rows() == 1280);
  for (Eigen::Index v = 0; v < sphere.vertices.rows(); ++v)
    REQUIRE(sphere.vertices.row(v).norm() == Approx(1.0).epsilon(1e-6));

  const TriangleSoup cylinder = read_triangle_soup(data + "/meshes/cylinder.stl");
  CHECK(cylinder.faces.rows() == 416);
  const double z0 = cylinder.vertices.col(2).minCoeff();
  CHECK(cylinder.vertices.col(2).maxCoeff() - z0 == Approx(8.0).epsilon(1e-6));
  CHECK(cylinder.vertices.leftCols<2>().rowwise().norm().maxCoeff() == Approx(1.0).epsilon(1e-6));
  for (Eigen::Index v = 0; v < cylinder.vertices.rows(); ++v) {
    // The rim has radius 1; the caps carry a few interior vertices.
    REQUIRE(cylinder.vertices.row(v).head<2>().norm() <= 1.0 + 1e-6);
    const double z = cylinder.vertices(v, 2) - z0;
    REQUIRE((z == Approx(0.0).margin(1e-6) || z == Approx(8.0).epsilon(1e-6)));
  }
  CHECK(read_triangle_soup(data + "/meshes/box.STL").faces.rows() == 8954);
  CHECK(read_triangle_soup(data + "/meshes/teapot.stl").faces.rows() == 894);
}

TEST_CASE("unreadable inputs are input errors naming the file and the problem") {
  CHECK_THAT(message_of(data + "/no/such/file.stl"), Catch::Contains("no such file"));
  CHECK_THAT(message_of(data + "/bad"), Catch::Contains("is a directory"));
  CHECK_THAT(message_of(data + "/bad/empty.stl"), Catch::Contains("empty"));
  CHECK_THAT(message_of(data + "/bad/cube.xyz"), Catch::Contains("unsupported file extension"));
  CHECK_THAT(message_of(data + "/bad/truncated_binary.stl"), Catch::Contains("truncated"));
  CHECK_THAT(message_of(data + "/bad/truncated_ascii.stl"), Catch::Contains("truncated"));
  CHECK_THAT(message_of(data + "/bad/count_mismatch.stl"), Catch::Contains("announces 100"));
  CHECK_THAT(message_of(data + "/bad/garbage_numbers.stl"),
             Catch::Contains("'zero' is not a number"));
  CHECK_THAT(message_of(data + "/bad/nan_coordinate.stl"), Catch::Contains("not finite"));
  CHECK_THAT(message_of(data + "/bad/inf_coordinate_binary.stl"), Catch::Contains("non-finite"));
  CHECK_THAT(message_of(data + "/bad/bad_index.obj"), Catch::Contains("vertex number 99"));
  CHECK_THAT(message_of(data + "/bad/not_a_mesh.stl"), Catch::Contains("not an ASCII STL"));
  CHECK_THAT(message_of(data + "/bad/empty.stl"), Catch::StartsWith(data + "/bad/empty.stl: "));
}

TEST_CASE("a FIFO given as the input is refused at once, also when running as root") {
  // Opening a FIFO for reading blocks until a writer appears; the reader must neither block
  // nor read it. This case needs no permissions, so it runs as root too.
  const auto fifo = std::filesystem::temp_directory_path() /
                    ("bemshape_test_fifo_" + std::to_string(::getpid()) + ".stl");
  std::filesystem::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const auto start = std::chrono::steady_clock::now();
  const std::string message = message_of(fifo.string());
  std::filesystem::remove(fifo);
  CHECK_THAT(message, Catch::StartsWith(fifo.string() + ": is a FIFO (named pipe), not a regular"));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(1));
  CHECK_THAT(message_of("/dev/null"), Catch::Contains("is a character device"));
}

TEST_CASE("a small file claiming billions of triangles is rejected without reading them") {
  const auto start = std::chrono::steady_clock::now();
  CHECK_THAT(message_of(data + "/bad/claims_4e9_triangles.stl"),
             Catch::Contains("announces 4000000000 triangles"));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::milliseconds(100));
}

TEST_CASE("binary STL written and read back keeps float32 coordinates and orientation") {
  const SurfaceMesh box = make_box(Eigen::Vector3d(-1, 0, 2), Eigen::Vector3d(0.5, 1, 3), 0.25);
  const auto path = std::filesystem::temp_directory_path() / "bemshape_test_roundtrip.stl";
  write_binary_stl(path, box.vertices(), box.faces());
  const TriangleSoup soup = read_triangle_soup(path);
  std::filesystem::remove(path);
  CHECK(soup.faces.rows() == box.num_faces());
  CHECK(soup.vertices.rows() == box.num_vertices());  // the STL reader merges exact copies
  CHECK(soup_volume(soup.vertices, soup.faces) == Approx(1.5).epsilon(1e-12));
}
