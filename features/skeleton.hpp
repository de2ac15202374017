#pragma once
// Skeleton (medial surface) function (paper, section "Skeleton function"):
//   f_s = P(|s̃|/λ)·χ,  s̃ = s·x_d,  λ = λd,
// with P the pulse of half-width w (1 on [−w, w], 0 elsewhere) and (λd, x_d) the LARGEST
// eigenpair of the feature tensor. Across a wall s ≈ λd·(x − x_mid) along x_d, so |s̃|/λd is
// the distance to the wall's mid-surface [model units].
//
// The paper writes λ1 and s̃1 with eigenvalues in ascending order; taken literally that
// picks the direction along the wall, where both s̃ and λ vanish, so bemshape uses the
// largest eigenpair (docs/theory.md explains).
//
// Where λd ≤ 0 there is no wall to be in the middle of: the distance is reported as
// infinite and the point is not on the skeleton.

#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "features/feature_tensor.hpp"

namespace bemshape::features {

/// Distance to the mid-surface |s·x_d|/λd [model units]; +∞ where λd ≤ 0.
template <int D>
double medial_distance(const Eigen::Matrix<double, D, 1>& s, const FeatureTensor<D>& tensor) {
  const double lambda = tensor.eigenvalues(D - 1);
  if (!(lambda > 0.0)) return std::numeric_limits<double>::infinity();
  return std::abs(s.dot(tensor.eigenvectors.col(D - 1))) / lambda;
}

/// f_s: true where the point lies within `width` of the mid-surface.
template <int D>
bool on_skeleton(const Eigen::Matrix<double, D, 1>& s, const FeatureTensor<D>& tensor,
                 double width) {
  return medial_distance(s, tensor) <= width;
}

}  // namespace bemshape::features
