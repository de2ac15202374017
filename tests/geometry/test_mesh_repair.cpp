#include <catch2/catch.hpp>

#include "geometry/mesh_repair.hpp"
#include "geometry/mesh_validation.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape::geometry;

TEST_CASE("duplicate and collapsed faces are dropped without opening the surface") {
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0.5);
  Eigen::MatrixX3i f(box.num_faces() + 3, 3);
  f << box.faces(), box.faces().row(2), box.faces()(5, 0), box.faces()(5, 0), box.faces()(5, 1),
      box.faces().row(9);
  const FaceCleanup c = remove_degenerate_faces(box.vertices(), f);
  CHECK(c.duplicates_removed == 2);
  CHECK(c.collapsed_removed == 1);
  CHECK(c.faces.rows() == box.num_faces());
  CHECK(validate_mesh(c.vertices, c.faces).closed_manifold());
}

TEST_CASE("a zero-area face is removed by splitting its neighbour and the surface is unchanged") {
  // Unit cube of 12 triangles with the top edge p=(1,1,1), q=(0,1,1) split at its midpoint m
  // on one side only: the collinear face (p, q, m) closes the surface.
  Eigen::MatrixX3d v(9, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1, 0.5, 1, 1;
  Eigen::MatrixX3i f(14, 3);
  f << 0, 2, 3, 0, 3, 1, 4, 5, 7, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1,
      7, 5, 4, 7, 8, 4, 8, 6, 7, 6, 8;
  const SurfaceMesh before(v, f);
  REQUIRE(validate_mesh(v, f).closed_manifold());
  REQUIRE(validate_mesh(v, f).zero_area_faces.count == 1);
  REQUIRE(validate_mesh(v, f).inconsistent_edges.count == 0);

  const FaceCleanup c = remove_degenerate_faces(v, f);
  CHECK(c.zero_area_removed == 1);
  CHECK(c.zero_area_left == 0);
  CHECK(c.faces.rows() == 14);  // −1 degenerate, −1 neighbour, +2 halves
  const MeshValidation after = validate_mesh(c.vertices, c.faces);
  CHECK(after.closed_manifold());
  CHECK(!after.zero_area_faces);
  CHECK(!after.inconsistent_edges);
  const SurfaceMesh repaired(c.vertices, c.faces);
  CHECK(repaired.signed_volume() == Approx(1.0).epsilon(1e-14));
  CHECK(repaired.area() == Approx(6.0).epsilon(1e-14));
}

TEST_CASE("a zero-area face on a hole is left for validation to refuse") {
  Eigen::MatrixX3d v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  Eigen::MatrixX3i f(1, 3);
  f << 0, 1, 2;
  const FaceCleanup c = remove_degenerate_faces(v, f);
  CHECK(c.zero_area_removed == 0);
  CHECK(c.zero_area_left == 1);
}
