#pragma once
// Orientation vectors of the shape-feature solution (paper, section "Orientation vector
// function"):
//   n_f = s/|s|                                     normal orientation (unit, dimensionless)
//   t_f: in 2-D the rotation of n_f by +90°; in 3-D the two eigenvectors of the feature
//        tensor S orthogonal to the eigenvector of its largest eigenvalue λd (the
//        directions along the wall).
// Where |s| ≤ kMinOrientationNorm·h0 (the mid-surface of a wall, where s changes sign, and
// far outside) n_f is the zero vector: there is no defined normal direction.

#include <Eigen/Core>

#include "features/feature_tensor.hpp"

namespace bemshape::features {

/// |s| below this multiple of h0 has no direction. s is of order h0 inside walls (s ~ x/(ã
/// κ) with ã·κ = 2h0), so 1e-12·h0 is rounding noise.
inline constexpr double kMinOrientationNorm = 1e-12;

template <int D>
Eigen::Matrix<double, D, 1> normal_orientation(const Eigen::Matrix<double, D, 1>& s, double h0) {
  const double norm = s.norm();
  if (!(norm > kMinOrientationNorm * h0)) return Eigen::Matrix<double, D, 1>::Zero();
  return s / norm;
}

/// 2-D tangential orientation: n_f rotated by +90° (zero where n_f is zero).
inline Eigen::Vector2d tangential_orientation(const Eigen::Vector2d& n_f) {
  return Eigen::Vector2d(-n_f.y(), n_f.x());
}

/// 3-D tangential orientations: the eigenvectors of λ1 and λ2 (columns 0 and 1).
inline Eigen::Matrix<double, 3, 2> tangential_orientation(const FeatureTensor<3>& tensor) {
  return tensor.eigenvectors.leftCols<2>();
}

}  // namespace bemshape::features
