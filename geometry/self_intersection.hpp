#pragma once
// Self-intersections: pairs of faces whose interiors meet. A solid's boundary must not cross
// itself (nor may two shells cross each other); sharing a vertex or an edge is not an
// intersection, and neither is touching at a vertex or along an edge that two copies of one
// vertex share (bodies split apart at a non-manifold edge or vertex touch there). Decided
// with exact predicates by the rules of CGAL Polygon_mesh_processing::self_intersections.

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

namespace bemshape::geometry {

struct SelfIntersections {
  /// Intersecting face pairs.
  std::size_t pairs = 0;
  /// A point of the first pair (centroid of its first face) [model units].
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  /// The pairs (face indices, smaller first, sorted); at most a million are listed.
  std::vector<std::pair<Eigen::Index, Eigen::Index>> face_pairs;
};

/// Finds every intersecting face pair of a triangle soup (any orientation, any number of
/// faces per edge). Vertices with equal coordinates count as one vertex.
///   vertices: #V×3 [model units]; faces: #F×3.
SelfIntersections find_self_intersections(const Eigen::MatrixX3d& vertices,
                                          const Eigen::MatrixX3i& faces);

}  // namespace bemshape::geometry
