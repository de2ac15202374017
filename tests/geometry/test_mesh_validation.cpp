#include <catch2/catch.hpp>

#include "geometry/mesh_validation.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape::geometry;

namespace {

/// A mesh without face `drop`.
Eigen::MatrixX3i without_face(const Eigen::MatrixX3i& f, Eigen::Index drop) {
  Eigen::MatrixX3i out(f.rows() - 1, 3);
  for (Eigen::Index i = 0, j = 0; i < f.rows(); ++i)
    if (i != drop)
      out.row(j++) = f.row(i);
  return out;
}

/// Regular tetrahedron-like solid: 4 vertices, outward faces.
void tetrahedron(Eigen::MatrixX3d& v, Eigen::MatrixX3i& f) {
  v.resize(4, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  f.resize(4, 3);
  f << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
}

}  // namespace

TEST_CASE("closed primitives break no rule") {
  const SurfaceMesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0.3);
  const MeshValidation r = validate_mesh(box.vertices(), box.faces());
  CHECK(r.closed_manifold());
  CHECK(!r.collapsed_faces);
  CHECK(!r.zero_area_faces);
  CHECK(!r.duplicate_faces);
  CHECK(!r.inconsistent_edges);
  CHECK(r.shells == 1);
  const SurfaceMesh two = concatenated(make_geodesic_sphere(1.0, 3),
                                       make_geodesic_sphere(1.0, 2, Eigen::Vector3d(5, 0, 0)));
  CHECK(validate_mesh(two.vertices(), two.faces()).shells == 2);
}

TEST_CASE("a missing face leaves three boundary edges located on it") {
  Eigen::MatrixX3d v;
  Eigen::MatrixX3i f;
  tetrahedron(v, f);
  const MeshValidation r = validate_mesh(v, without_face(f, 3));
  CHECK(r.boundary_edges.count == 3);
  CHECK(!r.nonmanifold_edges);
  CHECK(!r.closed_manifold());
  // The first boundary edge is one of the missing face's edges: its midpoint has x+y+z = 1.
  CHECK(r.boundary_edges.first.sum() == Approx(1.0));
}

TEST_CASE("two tetrahedra sharing an edge or a vertex are non-manifold") {
  Eigen::MatrixX3d v;
  Eigen::MatrixX3i f;
  tetrahedron(v, f);
  // Mirror through the edge (0,0,0)-(0,0,1): x,y → −x,−y shares vertices 0 and 3.
  Eigen::MatrixX3d v2(6, 3);
  v2 << v, -1, 0, 0, 0, -1, 0;
  Eigen::MatrixX3i f2(8, 3);
  f2 << f, 0, 5, 4, 0, 4, 3, 0, 3, 5, 4, 5, 3;
  MeshValidation r = validate_mesh(v2, f2);
  CHECK(r.nonmanifold_edges.count == 1);
  CHECK(r.nonmanifold_edges.first.isApprox(Eigen::Vector3d(0, 0, 0.5)));
  CHECK(!r.boundary_edges);

  // Sharing only vertex 3 = (0,0,1): a second tetrahedron above it.
  Eigen::MatrixX3d v3(7, 3);
  v3 << v, 0, 0, 2, 1, 0, 1, 0, 1, 1;
  Eigen::MatrixX3i f3(8, 3);
  f3 << f, 3, 5, 4, 3, 4, 6, 3, 6, 5, 4, 5, 6;
  r = validate_mesh(v3, f3);
  CHECK(!r.nonmanifold_edges);
  CHECK(r.nonmanifold_vertices.count == 1);
  CHECK(r.nonmanifold_vertices.first.isApprox(Eigen::Vector3d(0, 0, 1)));
}

TEST_CASE("collapsed, zero-area, needle and duplicate faces are counted") {
  Eigen::MatrixX3d v(6, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 1, 1e-5, 0, 0.5, 0, 0;
  Eigen::MatrixX3i f(6, 3);
  f << 0, 1, 2,  // fine
      2, 1, 0,   // duplicate of the first (other orientation)
      0, 0, 1,   // collapsed
      0, 5, 1,   // collinear: zero area
      0, 3, 4,   // height 1e-5 over length 2: needle
      0, 1, 2;   // duplicate again
  const MeshValidation r = validate_mesh(v, f);
  CHECK(r.collapsed_faces.count == 1);
  CHECK(r.zero_area_faces.count == 1);
  CHECK(r.zero_area_faces.first.isApprox(Eigen::Vector3d(0.5, 0, 0)));
  CHECK(r.needle_faces.count == 1);
  CHECK(r.duplicate_faces.count == 2);
  CHECK(relative_height(v, f, 4) == Approx(2.0 * 1e-5 / 4.0));
}

TEST_CASE("one reversed face makes its three edges inconsistent") {
  const SurfaceMesh sphere = make_geodesic_sphere(1.0, 4);
  Eigen::MatrixX3i f = sphere.faces();
  std::swap(f(7, 1), f(7, 2));
  const MeshValidation r = validate_mesh(sphere.vertices(), f);
  CHECK(r.inconsistent_edges.count == 3);
  CHECK(r.closed_manifold());
}
