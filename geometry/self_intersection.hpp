#pragma once
// Self-intersections: pairs of faces whose interiors meet. A solid's boundary must not cross
// itself (nor may two shells cross each other); sharing a vertex or an edge is not an
// intersection. Decided with exact predicates by CGAL Polygon_mesh_processing.

#include <Eigen/Core>
#include <cstddef>

namespace bemshape::geometry {

struct SelfIntersections {
  /// Intersecting face pairs.
  std::size_t pairs = 0;
  /// A point of the first pair (centroid of its first face) [model units].
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  /// Faces of non-manifold configurations, which the test cannot cover.
  std::size_t faces_not_tested = 0;
};

/// Finds every intersecting face pair. The faces must be consistently oriented (see
/// orient_consistently) and free of zero-area faces.
///   vertices: #V×3 [model units]; faces: #F×3.
SelfIntersections find_self_intersections(const Eigen::MatrixX3d& vertices,
                                          const Eigen::MatrixX3i& faces);

}  // namespace bemshape::geometry
