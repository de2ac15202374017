#include <catch2/catch.hpp>

#include "geometry/mesh_validation.hpp"
#include "geometry/nonmanifold_split.hpp"
#include "geometry/primitive_meshes.hpp"
#include "geometry/self_intersection.hpp"
#include "geometry/vertex_welding.hpp"

using namespace bemshape::geometry;

namespace {

/// The two meshes concatenated and welded (shared positions become shared vertices).
WeldResult welded(const SurfaceMesh& a, const SurfaceMesh& b) {
  const SurfaceMesh both = concatenated(a, b);
  return weld_vertices(both.vertices(), both.faces());
}

}  // namespace

TEST_CASE("a manifold mesh is left as it is") {
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3), 0.5);
  const NonmanifoldSplit s = split_nonmanifold(box.vertices(), box.faces());
  CHECK(s.edges_split == 0);
  CHECK(s.vertices_split == 0);
  CHECK(s.vertices == box.vertices());
  CHECK(s.faces == box.faces());
}

TEST_CASE("two cubes sharing an edge become two closed cubes touching along it") {
  const SurfaceMesh a = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 1.0);
  const SurfaceMesh b = make_box(Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(2, 2, 1), 1.0);
  const WeldResult w = welded(a, b);
  REQUIRE(validate_mesh(w.vertices, w.faces).nonmanifold_edges.count == 1);
  const NonmanifoldSplit s = split_nonmanifold(w.vertices, w.faces);
  CHECK(s.edges_split == 1);
  CHECK(s.first_edge.isApprox(Eigen::Vector3d(1, 1, 0.5)));
  CHECK(s.faces_unpaired == 0);
  CHECK(s.vertices_split == 2);  // the edge's two end points
  CHECK(s.copies_added == 2);
  const MeshValidation v = validate_mesh(s.vertices, s.faces);
  CHECK(v.closed_manifold());
  CHECK(!v.inconsistent_edges);
  CHECK(v.shells == 2);
  // Nothing moved, and touching along the edge is not an intersection.
  CHECK(SurfaceMesh(s.vertices, s.faces).signed_volume() == Approx(2.0).epsilon(1e-14));
  CHECK(find_self_intersections(s.vertices, s.faces).pairs == 0);
}

TEST_CASE("the split pairs faces of the same cube even when one cube is inside out") {
  const SurfaceMesh a = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 1.0);
  const SurfaceMesh b = with_flipped_orientation(
      make_box(Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(2, 2, 1), 1.0));
  const WeldResult w = welded(a, b);
  const NonmanifoldSplit s = split_nonmanifold(w.vertices, w.faces);
  const MeshValidation v = validate_mesh(s.vertices, s.faces);
  CHECK(v.closed_manifold());
  CHECK(!v.inconsistent_edges);
  CHECK(v.shells == 2);
  CHECK(SurfaceMesh(s.vertices, s.faces).signed_volume() == Approx(0.0).margin(1e-14));
}

TEST_CASE("two cubes sharing a vertex get one copy of it each") {
  const SurfaceMesh a = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 1.0);
  const SurfaceMesh b = make_box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(2, 2, 2), 1.0);
  const WeldResult w = welded(a, b);
  REQUIRE(validate_mesh(w.vertices, w.faces).nonmanifold_vertices.count == 1);
  const NonmanifoldSplit s = split_nonmanifold(w.vertices, w.faces);
  CHECK(s.edges_split == 0);
  CHECK(s.vertices_split == 1);
  CHECK(s.first_vertex.isApprox(Eigen::Vector3d(1, 1, 1)));
  CHECK(s.vertices.rows() == w.vertices.rows() + 1);
  const MeshValidation v = validate_mesh(s.vertices, s.faces);
  CHECK(v.closed_manifold());
  CHECK(v.shells == 2);
  CHECK(find_self_intersections(s.vertices, s.faces).pairs == 0);
}

TEST_CASE("three faces at an edge: the odd one keeps an open edge") {
  // A tetrahedron with a fin: a fourth triangle on one of its edges.
  Eigen::MatrixX3d v(5, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, -1, -1;
  Eigen::MatrixX3i f(5, 3);
  f << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 1, 4;
  const NonmanifoldSplit s = split_nonmanifold(v, f);
  CHECK(s.edges_split == 1);
  CHECK(s.faces_unpaired == 1);
  const MeshValidation after = validate_mesh(s.vertices, s.faces);
  CHECK(after.boundary_edges.count == 3);  // the fin alone
  CHECK(!after.nonmanifold_edges);
  CHECK(!after.nonmanifold_vertices);
  CHECK(after.shells == 2);
}
