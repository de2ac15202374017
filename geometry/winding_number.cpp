#include "geometry/winding_number.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace bemshape::geometry {

double winding_number(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                      const Eigen::Vector3d& point) {
  double total = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0)).transpose() - point;
    const Eigen::Vector3d b = vertices.row(faces(f, 1)).transpose() - point;
    const Eigen::Vector3d c = vertices.row(faces(f, 2)).transpose() - point;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * std::numbers::pi);
}

}  // namespace bemshape::geometry
