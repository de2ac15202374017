#include "geometry/closest_point.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "geometry/detail/cgal_spatial_queries.hpp"

namespace bemshape::geometry {

Eigen::Vector3d barycentric_coordinates(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Solve the 2×2 normal equations for p ≈ a + s(b − a) + t(c − a), then clamp to the
  // triangle: the input is already (up to rounding) on the triangle, so clamping only
  // removes rounding outside [0, 1].
  const Eigen::Vector3d e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  double s = 0.0, t = 0.0;
  if (det > 0.0) {
    s = (d22 * e1.dot(d) - d12 * e2.dot(d)) / det;
    t = (d11 * e2.dot(d) - d12 * e1.dot(d)) / det;
  }
  s = std::clamp(s, 0.0, 1.0);
  t = std::clamp(t, 0.0, 1.0);
  if (s + t > 1.0) {
    const double sum = s + t;
    s /= sum;
    t /= sum;
  }
  return Eigen::Vector3d(1.0 - s - t, s, t);
}

ClosestPointQuery::ClosestPointQuery(const SurfaceMesh& mesh)
    : vertices_(mesh.vertices()),
      faces_(mesh.faces()),
      tree_(std::make_unique<detail::TriangleTree>(vertices_, faces_)) {}

ClosestPointQuery::~ClosestPointQuery() = default;
ClosestPointQuery::ClosestPointQuery(ClosestPointQuery&&) noexcept = default;
ClosestPointQuery& ClosestPointQuery::operator=(ClosestPointQuery&&) noexcept = default;

ClosestPoint ClosestPointQuery::closest(const Eigen::Vector3d& query) const {
  const auto [face, point] = tree_->closest(query);
  ClosestPoint result;
  result.face = face;
  const Eigen::Vector3d a = vertices_.row(faces_(face, 0)), b = vertices_.row(faces_(face, 1)),
                        c = vertices_.row(faces_(face, 2));
  result.barycentric = barycentric_coordinates(point, a, b, c);
  result.point = result.barycentric(0) * a + result.barycentric(1) * b + result.barycentric(2) * c;
  result.distance = (query - result.point).norm();
  return result;
}

ClosestPoints ClosestPointQuery::closest_points(
    const Eigen::Ref<const Eigen::MatrixX3d>& queries) const {
  const Eigen::Index n = queries.rows();
  ClosestPoints result;
  result.faces.resize(n);
  result.barycentric.resize(n, 3);
  result.points.resize(n, 3);
  result.distances.resize(n);
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < n; ++i) {
    const ClosestPoint c = closest(Eigen::Vector3d(queries.row(i).transpose()));
    result.faces(i) = static_cast<int>(c.face);
    result.barycentric.row(i) = c.barycentric.transpose();
    result.points.row(i) = c.point.transpose();
    result.distances(i) = c.distance;
  }
  return result;
}

}  // namespace bemshape::geometry
