#pragma once
// LU factorisation with partial (row) pivoting, P·A = L·U, computed in place by panels of
// columns so that a long factorisation can be stopped between panels (core/cancellation.hpp)
// and can report its progress. Same algorithm and backward stability as LAPACK's dgetrf
// (right-looking, blocked): each panel of kLuPanelColumns columns is factorised column by
// column with the pivot of largest magnitude, its row swaps are applied to the rest of the
// matrix, then U₁₂ = L₁₁⁻¹A₁₂ and the trailing update A₂₂ −= L₂₁U₁₂ (a matrix product, where
// the time goes; Eigen runs it on all OpenMP threads).
//
// The result depends only on the matrix and the number of threads Eigen's product uses.

#include <Eigen/Core>

#include "core/progress.hpp"

namespace bemshape::linalg {

/// Columns per panel: wide enough that the trailing matrix product runs near peak speed,
/// narrow enough that a cancellation waits for at most one product of 2·N²·128 flops.
inline constexpr Eigen::Index kLuPanelColumns = 128;

/// The factors of a square matrix: `lu` holds U on and above the diagonal and the strictly
/// lower part of the unit lower-triangular L below it; row k was swapped with row
/// pivots(k) ≥ k at step k. A zero pivot (exactly singular matrix) is kept; solving with it
/// gives Inf/NaN, which the caller must check.
struct LuFactors {
  Eigen::MatrixXd lu;
  Eigen::VectorXi pivots;
};

/// Factorises `a` (N×N, moved in so the factorisation needs no second copy). Progress:
/// stage "factorise", fraction of the N³·2/3 flops done. Throws CancelledError between
/// panels if the run was cancelled.
LuFactors lu_factorise(Eigen::MatrixXd a, const ProgressCallback& progress = {});

/// Solves A·X = B (B: N×m) with the factors of A.
Eigen::MatrixXd lu_solve(const LuFactors& factors, const Eigen::Ref<const Eigen::MatrixXd>& b);

}  // namespace bemshape::linalg
