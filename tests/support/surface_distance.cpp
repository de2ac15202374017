#include "tests/support/surface_distance.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace bemshape::testing {

double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  // Inside the prism over the face: each edge function n·((q − p0) × (x − p0)) is a product of
  // an edge and a distance, accurate on a sliver (Ericson's region tests subtract products of
  // two long edges there and misplace the point).
  if (n2 > 0.0 && n.dot((b - a).cross(p - a)) >= 0.0 && n.dot((c - b).cross(p - b)) >= 0.0 &&
      n.dot((a - c).cross(p - c)) >= 0.0)
    return std::abs((p - a).dot(n)) / std::sqrt(n2);
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

double max_distance_to_surface(const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& vertices,
                               const Eigen::MatrixX3i& faces) {
  const Eigen::Index nf = faces.rows();
  std::vector<Eigen::Vector3d> lo(static_cast<std::size_t>(nf)), hi(static_cast<std::size_t>(nf));
  for (Eigen::Index f = 0; f < nf; ++f) {
    lo[static_cast<std::size_t>(f)] = vertices.row(faces(f, 0)).transpose();
    hi[static_cast<std::size_t>(f)] = lo[static_cast<std::size_t>(f)];
    for (int k = 1; k < 3; ++k) {
      lo[static_cast<std::size_t>(f)] =
          lo[static_cast<std::size_t>(f)].cwiseMin(vertices.row(faces(f, k)).transpose());
      hi[static_cast<std::size_t>(f)] =
          hi[static_cast<std::size_t>(f)].cwiseMax(vertices.row(faces(f, k)).transpose());
    }
  }
  double worst = 0.0;
#pragma omp parallel for reduction(max : worst) schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i).transpose();
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index f = 0; f < nf && best > 0.0; ++f) {
      const auto k = static_cast<std::size_t>(f);
      if ((lo[k] - p).cwiseMax(p - hi[k]).cwiseMax(0.0).norm() >= best)
        continue;
      best = std::min(best, triangle_distance(p, vertices.row(faces(f, 0)).transpose(),
                                              vertices.row(faces(f, 1)).transpose(),
                                              vertices.row(faces(f, 2)).transpose()));
    }
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace bemshape::testing
