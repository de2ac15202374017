#pragma once
// The shape feature tensor (paper, section "Shape feature tensor"):
//   S_ij = ½ (∂s_i/∂x_j + ∂s_j/∂x_i),
// its eigenvalues λ1 ≤ … ≤ λd and unit eigenvectors x_s^(1..d).
// Input: grad_s(i, j) = ∂s_i/∂x_j, a d×d matrix [dimensionless: s and x share model units].

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace bemshape::features {

template <int D>
struct FeatureTensor {
  using Matrix = Eigen::Matrix<double, D, D>;
  using Vector = Eigen::Matrix<double, D, 1>;
  Matrix tensor;        ///< S, symmetric
  Vector eigenvalues;   ///< λ1 ≤ … ≤ λd
  Matrix eigenvectors;  ///< column k is the unit eigenvector of λ_{k+1}
};

/// S = sym(∇s) and its ordered eigen-decomposition. Eigenvectors are only defined up to
/// sign; bemshape fixes the sign so that the component of largest magnitude is positive,
/// which makes results reproducible across platforms and thread counts.
template <int D>
FeatureTensor<D> feature_tensor(const Eigen::Matrix<double, D, D>& grad_s) {
  FeatureTensor<D> result;
  result.tensor = 0.5 * (grad_s + grad_s.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>> solver(result.tensor);
  result.eigenvalues = solver.eigenvalues();  // ascending
  result.eigenvectors = solver.eigenvectors();
  for (int k = 0; k < D; ++k) {
    Eigen::Index largest = 0;
    result.eigenvectors.col(k).cwiseAbs().maxCoeff(&largest);
    if (result.eigenvectors(largest, k) < 0.0) result.eigenvectors.col(k) *= -1.0;
  }
  return result;
}

}  // namespace bemshape::features
