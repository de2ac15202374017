#pragma once
// Preconditioned conjugate gradients for A·X = B with m right-hand sides that share the
// symmetric positive definite operator A (and preconditioner M ≈ A⁻¹). Each column runs
// its own CG recurrence (own step lengths α_j, β_j); the operator and the preconditioner
// are applied to all columns at once, which is what makes the shared operator pay off.
// A column stops updating once ‖b_j − A x_j‖₂ ≤ tolerance·‖b_j‖₂.
//
//   Operator:       void apply(const Eigen::MatrixXd& x, Eigen::MatrixXd& y) const  (y = A x)
//   Preconditioner: void apply(const Eigen::MatrixXd& r, Eigen::MatrixXd& z) const  (z = M r)

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "core/progress.hpp"

namespace bemshape::linalg {

struct ConjugateGradientReport {
  int iterations = 0;                      ///< iterations until the last column converged
  std::vector<double> relative_residuals;  ///< ‖b_j − A x_j‖/‖b_j‖ per column at the end
  bool converged = false;
};

/// Solves A·X = B from the initial guess X (#rows×m, resized to B's shape if it differs).
/// Throws NumericalError if a NaN appears or, when `throw_on_failure`, if some column has not
/// converged after max_iterations. Progress: stage "conjugate gradients", fraction from the
/// residual reduction on a log scale.
template <class Operator, class Preconditioner>
ConjugateGradientReport conjugate_gradient(const Operator& A, const Preconditioner& M,
                                           const Eigen::MatrixXd& B, Eigen::MatrixXd& X,
                                           double tolerance, int max_iterations,
                                           const ProgressCallback& progress = {},
                                           bool throw_on_failure = true) {
  const Eigen::Index m = B.cols();
  if (X.rows() != B.rows() || X.cols() != m)
    X.setZero(B.rows(), m);
  Eigen::MatrixXd R, Z, P, Q;
  A.apply(X, Q);
  R = B - Q;
  const Eigen::VectorXd b_norm = B.colwise().norm().transpose();
  std::vector<char> active(m, 1);
  Eigen::VectorXd r_norm = R.colwise().norm().transpose();
  auto is_done = [&](Eigen::Index j) { return !(r_norm[j] > tolerance * b_norm[j]); };
  for (Eigen::Index j = 0; j < m; ++j)
    active[j] = !is_done(j);

  ConjugateGradientReport report;
  M.apply(R, Z);
  P = Z;
  Eigen::VectorXd rz = (R.array() * Z.array()).colwise().sum().transpose();
  double start_ratio = 0.0;
  for (Eigen::Index j = 0; j < m; ++j)
    if (b_norm[j] > 0.0)
      start_ratio = std::max(start_ratio, r_norm[j] / b_norm[j]);

  for (int k = 0; k < max_iterations; ++k) {
    bool any = false;
    for (Eigen::Index j = 0; j < m; ++j)
      any = any || active[j];
    if (!any)
      break;
    throw_if_cancelled();
    A.apply(P, Q);
    const Eigen::VectorXd pq = (P.array() * Q.array()).colwise().sum().transpose();
    for (Eigen::Index j = 0; j < m; ++j) {
      if (!active[j])
        continue;
      const double alpha = rz[j] / pq[j];
      if (!std::isfinite(alpha))
        throw NumericalError("conjugate gradients: step length is not finite at iteration " +
                             std::to_string(k + 1) + " (right-hand side " + std::to_string(j) +
                             "); the operator is not positive definite or the data contain "
                             "NaN");
      X.col(j) += alpha * P.col(j);
      R.col(j) -= alpha * Q.col(j);
    }
    r_norm = R.colwise().norm().transpose();
    if (!r_norm.allFinite())
      throw NumericalError(
          "conjugate gradients: the residual became NaN or infinite at "
          "iteration " +
          std::to_string(k + 1) + "; check the input data");
    report.iterations = k + 1;
    double worst = 0.0;
    for (Eigen::Index j = 0; j < m; ++j) {
      if (active[j] && is_done(j))
        active[j] = 0;
      if (active[j])
        worst = std::max(worst, r_norm[j] / b_norm[j]);
    }
    if (progress && start_ratio > 0.0 && worst > 0.0) {
      const double done = std::log(start_ratio / worst) / std::log(start_ratio / tolerance);
      report_progress(progress, "conjugate gradients", std::clamp(done, 0.0, 1.0));
    }
    M.apply(R, Z);
    const Eigen::VectorXd rz_next = (R.array() * Z.array()).colwise().sum().transpose();
    for (Eigen::Index j = 0; j < m; ++j) {
      if (!active[j])
        continue;
      const double beta = rz_next[j] / rz[j];
      P.col(j) = Z.col(j) + beta * P.col(j);
    }
    rz = rz_next;
  }
  report.relative_residuals.resize(m);
  report.converged = true;
  for (Eigen::Index j = 0; j < m; ++j) {
    report.relative_residuals[j] = b_norm[j] > 0.0 ? r_norm[j] / b_norm[j] : 0.0;
    report.converged = report.converged && is_done(j);
  }
  if (!report.converged && throw_on_failure)
    throw NumericalError("conjugate gradients did not reach the relative residual " +
                         std::to_string(tolerance) + " in " + std::to_string(max_iterations) +
                         " iterations; raise the iteration limit or check the input");
  return report;
}

}  // namespace bemshape::linalg
