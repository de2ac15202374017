#pragma once
// Distance from points to a triangle mesh: the distance to the face's plane where the point
// lies over the face (decided by the signs of the three edge functions), else to the nearest
// edge. Exact to rounding also on CAD slivers, where barycentric coordinates lose the digits
// (geometry::ClosestPointQuery reports 4e−7 for a point on a plate's face built of slivers)
// and so do region tests that subtract products of two long edges. Brute force over the
// faces behind a bounding-box test: for test meshes only.

#include <Eigen/Core>

namespace bemshape::testing {

/// Distance from p to the triangle (a, b, c) [model units].
double triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Distance from p to the segment [a, b] [model units].
double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b);

/// Largest distance from a row of `points` (#P×3) to the surface (vertices #V×3, faces #F×3).
double max_distance_to_surface(const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& vertices,
                               const Eigen::MatrixX3i& faces);

}  // namespace bemshape::testing
