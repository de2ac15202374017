#pragma once
// Internal: CGAL's AABB tree and Side_of_triangle_mesh behind opaque classes with Eigen
// types, compiled in one translation unit (cgal_spatial_queries.cpp). Use closest_point.hpp
// and point_inside.hpp instead.

#include <Eigen/Core>
#include <memory>

namespace bemshape::geometry::detail {

/// AABB tree over the non-degenerate triangles of a mesh. Built eagerly in the constructor
/// (including the distance-query acceleration), so const queries are thread-safe.
class TriangleTree {
 public:
  TriangleTree(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);
  ~TriangleTree();
  TriangleTree(TriangleTree&&) noexcept;
  TriangleTree& operator=(TriangleTree&&) noexcept;

  /// Nearest point of the surface to `x` and the index of the input face it lies on.
  std::pair<Eigen::Index, Eigen::Vector3d> closest(const Eigen::Vector3d& x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// CGAL::Side_of_triangle_mesh (ray casting with exact predicates) on a closed mesh.
class SideOfTriangleMesh {
 public:
  /// Throws InputError if the faces do not form a closed 2-manifold.
  SideOfTriangleMesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);
  ~SideOfTriangleMesh();
  SideOfTriangleMesh(SideOfTriangleMesh&&) noexcept;
  SideOfTriangleMesh& operator=(SideOfTriangleMesh&&) noexcept;

  /// +1 strictly inside, 0 on the surface, −1 outside.
  int side(const Eigen::Vector3d& x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bemshape::geometry::detail
