#pragma once
// Restarted GMRES(m) (Saad & Schultz 1986; Saad, "Iterative Methods for Sparse Linear
// Systems", §9.3) with the preconditioner M⁻¹ on either side, modified Gram–Schmidt
// Arnoldi and Givens rotations:
//   right — minimises ‖b − A M⁻¹u‖ over Krylov spaces of A M⁻¹, x = M⁻¹u. The residual it
//           monitors is the true one: `tolerance` means ‖b − A x‖ ≤ tol·‖b‖.
//   left  — minimises ‖M⁻¹(b − A x)‖ over Krylov spaces of M⁻¹A: `tolerance` means
//           ‖M⁻¹(b − A x)‖ ≤ tol·‖M⁻¹b‖. When M⁻¹ approximates A⁻¹, M⁻¹(b − A x)
//           approximates the error A⁻¹b − x, so this bounds the solution's error rather than
//           the equations' mismatch. For a first-kind operator (condition number growing
//           like 1/h) the two differ by that condition number.
// Either way the final true residual is recomputed from scratch and reported.
//
// Several right-hand sides with the same A (the three coordinate directions of the
// transmission problem) are solved by `gmres_columns`: one GMRES per column, run in
// lockstep so that every step applies A and M⁻¹ to all unfinished columns at once. An
// operator whose cost is reading its storage (an H-matrix, a sparse matrix, block LU
// factors) then reads it once per step for all columns instead of once per column. Each
// column's iterates are those of a GMRES on that column alone: nothing is shared between
// the columns' Krylov spaces (this is not block GMRES), so the iteration counts are too.

#include <functional>
#include <vector>

#include <Eigen/Core>

namespace bemshape::linalg {

/// y = A x (or y = M⁻¹ x for a preconditioner); y is sized by the caller's operator.
using LinearOperator = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& y)>;

/// Y = A X column by column, X with one column per vector (or Y = M⁻¹ X); Y is sized by
/// the operator.
using ColumnsOperator = std::function<void(const Eigen::MatrixXd& x, Eigen::MatrixXd& y)>;

/// Which side of A the preconditioner is applied on (see above).
enum class PreconditionerSide { right, left };

struct GmresOptions {
  double tolerance = 1e-6;   ///< relative residual to reach: ‖b − A x‖/‖b‖ (right),
                             ///< ‖M⁻¹(b − A x)‖/‖M⁻¹b‖ (left)
  PreconditionerSide side = PreconditionerSide::right;
  int restart = 60;          ///< Krylov dimension m before a restart
  int max_iterations = 600;  ///< total matrix–vector products allowed
};

struct GmresResult {
  int iterations = 0;     ///< matrix–vector products with A (Arnoldi steps)
  double residual = 0.0;  ///< ‖b − A x‖/‖b‖ recomputed at the end
  /// ‖M⁻¹(b − A x)‖/‖M⁻¹b‖ at the end when preconditioned on the left (else = residual)
  double preconditioned_residual = 0.0;
  bool converged = false;
};

/// Solves A x = b starting from the given x (zero is fine). `preconditioner` may be empty
/// (identity). Never throws for non-convergence: the caller decides (GmresResult::converged).
GmresResult gmres(const LinearOperator& a, const LinearOperator& preconditioner,
                  const Eigen::VectorXd& b, Eigen::VectorXd& x, const GmresOptions& options = {},
                  const std::function<void(int iteration, double residual)>& monitor = {});

/// Solves A X = B column by column, in lockstep (see above), starting from the given X
/// (resized to B's shape and zeroed if its shape differs). One result per column.
/// `monitor(column, iteration, residual)` follows each Arnoldi step of a column with that
/// column's residual estimate; it may throw to stop the solve.
std::vector<GmresResult> gmres_columns(
    const ColumnsOperator& a, const ColumnsOperator& preconditioner, const Eigen::MatrixXd& b,
    Eigen::MatrixXd& x, const GmresOptions& options = {},
    const std::function<void(int column, int iteration, double residual)>& monitor = {});

}  // namespace bemshape::linalg
