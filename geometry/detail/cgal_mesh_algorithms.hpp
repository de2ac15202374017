#pragma once
// Internal: the CGAL Polygon_mesh_processing algorithms bemshape uses, behind plain Eigen
// types so that CGAL is compiled in one translation unit (cgal_mesh_algorithms.cpp) and
// never appears in a header. Not part of the public interface; use self_intersection.hpp
// and isotropic_remeshing.hpp.

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

namespace bemshape::geometry::detail {

struct CgalSelfIntersections {
  /// Pairs of faces that intersect other than in a shared vertex or edge.
  std::size_t pairs = 0;
  /// The pairs (face indices, smaller first), ascending; at most kMaxListedIntersections of
  /// them (the smallest).
  std::vector<std::pair<Eigen::Index, Eigen::Index>> list;
};

/// Enough pairs to locate and group every defect a repair could address (16 MB); a mesh
/// with more intersecting pairs is refused whatever they are.
inline constexpr std::size_t kMaxListedIntersections = 1'000'000;

/// Every pair of intersecting faces of a triangle soup, by the rules of
/// CGAL::Polygon_mesh_processing::self_intersections (exact predicates): faces sharing an
/// edge intersect only if they are coplanar and on the same side of it (a fold), faces
/// sharing a vertex only if an opposite edge meets the other face, other faces if they
/// meet at all; a degenerate face (two corners at one position, or collinear corners)
/// intersects every face whose box meets its own. "Shared" is decided by position, not by index: copies of one vertex made by
/// splitting a non-manifold edge or vertex count as the same vertex, so two bodies that
/// touch along an edge or at a point do not intersect. Box intersection (CGAL
/// box_self_intersection_d) finds the candidate pairs.
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
