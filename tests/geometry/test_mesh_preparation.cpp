#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>

#include "core/errors.hpp"
#include "geometry/mesh_preparation.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/primitive_meshes.hpp"
#include "geometry/self_intersection.hpp"

using namespace bemshape;
using namespace bemshape::geometry;

namespace {

const std::string data = BEMSHAPE_TEST_DATA_DIR;

TriangleSoup soup_of(const SurfaceMesh& mesh) {
  TriangleSoup soup;
  soup.vertices = mesh.vertices();
  soup.faces = mesh.faces();
  soup.format = "memory";
  return soup;
}

bool has_problem(const MeshReport& r, MeshProblem::Status status, const std::string& what) {
  for (const MeshProblem& p : r.problems)
    if (p.status == status && p.what.find(what) != std::string::npos)
      return true;
  return false;
}

}  // namespace

TEST_CASE("plate_holes: usable, one shell, dimensions and volume below the full plate") {
  const PreparedMesh p = prepare_mesh_file(data + "/meshes/plate_holes.STL");
  CHECK(p.report.usable());
  CHECK(p.report.shells == 1);
  CHECK(p.report.cavities == 0);
  CHECK(p.report.faces == 1252);
  CHECK(p.report.bounding_box.extent().isApprox(Eigen::Vector3d(203.2, 304.8, 12.7), 1e-6));
  CHECK(p.report.volume > 0.0);
  CHECK(p.report.volume < 203.2 * 304.8 * 12.7);
  const MeshValidation v = validate_mesh(p.mesh.vertices(), p.mesh.faces());
  CHECK(v.closed_manifold());
  CHECK(!v.inconsistent_edges);
}

TEST_CASE("unit_sphere and cylinder: volumes just below the smooth solids") {
  const PreparedMesh sphere = prepare_mesh_file(data + "/meshes/unit_sphere.STL");
  const double ball = 4.0 / 3.0 * std::numbers::pi;
  CHECK(sphere.report.volume < ball);
  CHECK(sphere.report.volume > 0.98 * ball);
  const PreparedMesh cylinder = prepare_mesh_file(data + "/meshes/cylinder.stl");
  const double rod = std::numbers::pi * 8.0;
  CHECK(cylinder.report.volume < rod);
  CHECK(cylinder.report.volume > 0.99 * rod);
  CHECK(cylinder.report.bounding_box.extent().isApprox(Eigen::Vector3d(2, 2, 8), 1e-6));
}

TEST_CASE("teapot: refused for its 64 open boundary edges") {
  const PreparedMesh p = inspect_mesh_file(data + "/meshes/teapot.stl");
  CHECK(!p.report.usable());
  bool found = false;
  for (const MeshProblem& q : p.report.problems)
    if (q.what.find("open boundary edges") != std::string::npos) {
      found = true;
      CHECK(q.count == 64);
      CHECK(q.status == MeshProblem::Status::refused);
    }
  CHECK(found);
  CHECK_THROWS_WITH(
      prepare_mesh_file(data + "/meshes/teapot.stl"),
      Catch::Contains("64 open boundary edges (first at ") && Catch::Contains("close the holes"));
}

TEST_CASE("box.STL: ten closed parts that overlap, refused as they are, united by repair") {
  MeshPreparationOptions strict;
  strict.repair_surface = false;
  const PreparedMesh p = inspect_mesh_file(data + "/meshes/box.STL", strict);
  CHECK(p.report.shells == 10);
  const MeshValidation v = validate_mesh(p.mesh.vertices(), p.mesh.faces());
  CHECK(v.closed_manifold());
  // Every part on its own is a valid solid ...
  std::size_t count = 0;
  const std::vector<int> label = shell_labels(p.mesh.faces(), &count);
  REQUIRE(count == 10);
  double sum = 0.0, largest = 0.0;
  for (int s = 0; s < 10; ++s) {
    std::vector<Eigen::Index> rows;
    for (Eigen::Index f = 0; f < p.mesh.num_faces(); ++f)
      if (label[static_cast<std::size_t>(f)] == s)
        rows.push_back(f);
    Eigen::MatrixX3i part(static_cast<Eigen::Index>(rows.size()), 3);
    for (std::size_t i = 0; i < rows.size(); ++i)
      part.row(static_cast<Eigen::Index>(i)) = p.mesh.faces().row(rows[i]);
    CHECK(find_self_intersections(p.mesh.vertices(), part).pairs == 0);
    const double volume = std::abs(SurfaceMesh(p.mesh.vertices(), part).signed_volume());
    sum += volume;
    largest = std::max(largest, volume);
  }
  // ... but together they overlap, which a single solid's boundary cannot.
  CHECK(!p.report.usable());
  CHECK(has_problem(p.report, MeshProblem::Status::refused, "intersecting faces"));

  // Repaired: the boundary of the union, one closed solid that holds every part.
  const PreparedMesh united = inspect_mesh_file(data + "/meshes/box.STL");
  CHECK(united.report.usable());
  CHECK(united.report.shells == 1);
  CHECK(has_problem(united.report, MeshProblem::Status::repaired, "overlapping bodies"));
  CHECK(validate_mesh(united.mesh.vertices(), united.mesh.faces()).closed_manifold());
  CHECK(find_self_intersections(united.mesh.vertices(), united.mesh.faces()).pairs == 0);
  CHECK(united.report.volume < sum);
  CHECK(united.report.volume > largest);
  CHECK(united.report.bounding_box.min.isApprox(p.report.bounding_box.min, 1e-12));
  CHECK(united.report.bounding_box.max.isApprox(p.report.bounding_box.max, 1e-12));
}

TEST_CASE("a shell whose cavity wall points outward is repaired, cavity counted") {
  const double r1 = 1.0, r2 = 2.0;
  const SurfaceMesh wrong =
      concatenated(make_geodesic_sphere(r2, 6), make_geodesic_sphere(r1, 4));  // both outward
  const PreparedMesh p = inspect_triangle_soup(soup_of(wrong), "shell");
  CHECK(p.report.usable());
  CHECK(p.report.shells == 2);
  CHECK(p.report.cavities == 1);
  CHECK(has_problem(p.report, MeshProblem::Status::repaired, "inside out"));
  const SurfaceMesh right = make_spherical_shell(r1, r2, 4, 6);
  CHECK(p.report.volume == Approx(right.signed_volume()).epsilon(1e-12));
}

TEST_CASE("inverted and partly inverted meshes are repaired, not refused") {
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3), 0.5);
  const PreparedMesh inverted = inspect_triangle_soup(soup_of(with_flipped_orientation(box)), "b");
  CHECK(inverted.report.usable());
  CHECK(inverted.mesh.signed_volume() == Approx(6.0).epsilon(1e-12));
  Eigen::MatrixX3i f = box.faces();
  std::swap(f(0, 1), f(0, 2));
  std::swap(f(9, 1), f(9, 2));
  const PreparedMesh partly = inspect_triangle_soup(soup_of(SurfaceMesh(box.vertices(), f)), "b");
  CHECK(partly.report.usable());
  CHECK(has_problem(partly.report, MeshProblem::Status::repaired, "opposite orientation"));
  CHECK(partly.mesh.signed_volume() == Approx(6.0).epsilon(1e-12));
  CHECK(!validate_mesh(partly.mesh.vertices(), partly.mesh.faces()).inconsistent_edges);
}

TEST_CASE("a welded STL soup gets shared vertices and the report counts what was merged") {
  // Every face with its own three corners, as STL stores them.
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0.5);
  TriangleSoup soup;
  soup.format = "memory";
  soup.vertices.resize(3 * box.num_faces(), 3);
  soup.faces.resize(box.num_faces(), 3);
  for (Eigen::Index f = 0; f < box.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      soup.vertices.row(3 * f + k) = box.vertices().row(box.faces()(f, k));
      soup.faces(f, k) = static_cast<int>(3 * f + k);
    }
  const PreparedMesh p = inspect_triangle_soup(soup, "soup");
  CHECK(p.report.usable());
  CHECK(p.report.vertices == static_cast<std::size_t>(box.num_vertices()));
  CHECK(p.report.repairs.front() == "merged " +
                                        std::to_string(3 * box.num_faces() - box.num_vertices()) +
                                        " vertices with exactly equal coordinates");
}
