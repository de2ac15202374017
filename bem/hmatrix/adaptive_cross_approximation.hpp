#pragma once
// Adaptive cross approximation with partial pivoting (Bebendorf 2000) of an m×n block
// A ≈ U·Vᵀ (U: m×k, V: n×k) from k of its rows and columns, followed by a QR/SVD
// recompression that makes the rank minimal for the tolerance.
//
// Step k: the residual row R(i_k, :) = A(i_k, :) − Σ_l U(i_k, l) V(:, l)ᵀ; column pivot j_k
// = argmax |R(i_k, j)|; v_k = R(i_k, :)/R(i_k, j_k); u_k = A(:, j_k) − Σ_l V(j_k, l) U(:, l);
// next row pivot i_{k+1} = argmax over unused rows of |u_k(i)|. Stops when
//   ‖u_k‖·‖v_k‖ ≤ ε·‖U Vᵀ‖_F,
// the usual estimate of the relative Frobenius error ‖A − U Vᵀ‖_F/‖A‖_F (exact for
// asymptotically smooth kernels on admissible blocks, where the singular values decay
// geometrically). ‖U Vᵀ‖_F is tracked as Σ_l ‖u_l‖²‖v_l‖² and made exact from the Gram
// matrices UᵀU and VᵀV when the test is about to pass; recompression reuses those Gram
// matrices. Recompression: U = Q_u R_u, V = Q_v R_v (by Cholesky factors of the Gram
// matrices where the columns allow, by Householder reflections otherwise), B = R_u R_vᵀ, and
// the truncated SVD of B: keep the smallest r with (Σ_{i>r} σ_i²)^{1/2} ≤ ε·‖B‖_F. The singular vectors
// come from the eigenvectors of BᵀB with the truncation measured on B itself (see
// recompress): the SVD's ranks at a fifth of its cost.

#include <functional>
#include <optional>

#include <Eigen/Core>

namespace bemshape::bem {

/// A ≈ U·Vᵀ.
struct LowRankBlock {
  Eigen::MatrixXd U;  ///< m×k
  Eigen::MatrixXd V;  ///< n×k
  Eigen::Index rank() const { return U.cols(); }
};

/// Writes row i (length n) / column j (length m) of A.
using RowGenerator = std::function<void(Eigen::Index i, Eigen::Ref<Eigen::VectorXd> row)>;
using ColumnGenerator = std::function<void(Eigen::Index j, Eigen::Ref<Eigen::VectorXd> column)>;

/// Partial-pivot ACA of the m×n block with relative tolerance `epsilon`, recompressed.
/// Returns nothing if the rank reaches `max_rank` before converging (the caller then stores
/// the block densely: a low-rank form would be no smaller).
std::optional<LowRankBlock> adaptive_cross_approximation(Eigen::Index m, Eigen::Index n,
                                                         const RowGenerator& row,
                                                         const ColumnGenerator& column,
                                                         double epsilon, Eigen::Index max_rank);

/// How recompress finds orthonormal bases of U's and V's columns: from their Gram matrices
/// (Cholesky, columns scaled to unit norm) where the columns are conditioned well enough for
/// ε, by Householder reflections otherwise; or always by Householder reflections.
enum class FactorBases { gram_where_conditioned, householder };

/// The smallest-rank U'·V'ᵀ within relative Frobenius distance `epsilon` of U·Vᵀ (to
/// rounding: the rank of the truncated SVD, unless singular values lie within rounding of
/// each other, where it may keep one more). U' has orthogonal columns of norms σ_i, V'
/// orthonormal ones.
LowRankBlock recompress(const LowRankBlock& block, double epsilon,
                        FactorBases bases = FactorBases::gram_where_conditioned);

/// Whether recompress(block, epsilon) takes the Gram route for both factors.
bool recompression_uses_gram_bases(const LowRankBlock& block, double epsilon);

}  // namespace bemshape::bem
