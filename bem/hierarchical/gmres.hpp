#pragma once
// Restarted GMRES(m) with right preconditioning (Saad & Schultz 1986; Saad, "Iterative
// Methods for Sparse Linear Systems", §9.3.2): solves A x = b by minimising ‖b − A M⁻¹ u‖
// over Krylov spaces of A M⁻¹, x = M⁻¹ u. With right preconditioning the residual GMRES
// monitors is the true residual of A x = b, so `tolerance` means ‖b − A x‖ ≤ tol·‖b‖.
// Modified Gram–Schmidt Arnoldi, Givens rotations; the final residual is recomputed from
// scratch and reported.

#include <functional>

#include <Eigen/Core>

namespace bemshape::bem {

/// y = A x (or y = M⁻¹ x for a preconditioner); y is sized by the caller's operator.
using LinearOperator = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& y)>;

struct GmresOptions {
  double tolerance = 1e-6;   ///< relative residual ‖b − A x‖/‖b‖ to reach
  int restart = 60;          ///< Krylov dimension m before a restart
  int max_iterations = 600;  ///< total matrix–vector products allowed
};

struct GmresResult {
  int iterations = 0;     ///< matrix–vector products with A (Arnoldi steps)
  double residual = 0.0;  ///< ‖b − A x‖/‖b‖ recomputed at the end
  bool converged = false;
};

/// Solves A x = b starting from the given x (zero is fine). `preconditioner` may be empty
/// (identity). Never throws for non-convergence: the caller decides (GmresResult::converged).
GmresResult gmres(const LinearOperator& a, const LinearOperator& preconditioner,
                  const Eigen::VectorXd& b, Eigen::VectorXd& x, const GmresOptions& options = {},
                  const std::function<void(int iteration, double residual)>& monitor = {});

}  // namespace bemshape::bem
