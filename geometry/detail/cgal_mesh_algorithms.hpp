#pragma once
// Internal: the CGAL Polygon_mesh_processing algorithms bemshape uses, behind plain Eigen
// types so that CGAL is compiled in one translation unit (cgal_mesh_algorithms.cpp) and
// never appears in a header. Not part of the public interface; use self_intersection.hpp
// and isotropic_remeshing.hpp.

#include <Eigen/Core>
#include <cstddef>
#include <utility>

namespace bemshape::geometry::detail {

struct CgalSelfIntersections {
  /// Pairs of faces whose interiors intersect (sharing a vertex or edge is not counted).
  std::size_t pairs = 0;
  /// Face indices of the first pair (−1 if none).
  std::pair<Eigen::Index, Eigen::Index> first{-1, -1};
  /// Faces that could not be put into a halfedge mesh (non-manifold): not tested.
  std::size_t faces_not_tested = 0;
};

/// CGAL::Polygon_mesh_processing::self_intersections on a consistently oriented mesh
/// (exact predicates).
CgalSelfIntersections cgal_self_intersections(const Eigen::MatrixX3d& vertices,
                                              const Eigen::MatrixX3i& faces);

struct CgalRemeshParameters {
  double target_edge = 0.0;
  double sharp_angle_degrees = 0.0;
  unsigned iterations = 0;
  /// After remeshing, edges longer than this are split and the new vertices projected back
  /// onto the input surface.
  double max_edge = 0.0;
};

struct CgalRemeshResult {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  std::size_t sharp_edges = 0;
};

/// CGAL::Polygon_mesh_processing::isotropic_remeshing of a closed, consistently oriented
/// mesh with the edges found by detect_sharp_edges(sharp_angle_degrees) constrained.
CgalRemeshResult cgal_isotropic_remesh(const Eigen::MatrixX3d& vertices,
                                       const Eigen::MatrixX3i& faces,
                                       const CgalRemeshParameters& parameters);

}  // namespace bemshape::geometry::detail
