#pragma once
// Nested cluster bases (the H² form) of the low-rank blocks of an H-matrix's far field,
// converted from their factors: one orthonormal basis per cluster and side instead of a pair
// of factors per block. A measurement, not part of the library: `bench_fast_path
// nested-bases` compares its storage with the H-matrix's, and the solver's H² far field
// (bem/hmatrix/nested_far_field.hpp) is built from the kernel instead, never holding the
// H-matrix this conversion reads.
//
// An H-matrix stores every admissible block b = (τ, σ) as its own factors, A_b ≈ U_b V_bᵀ,
// so a cluster's rows carry a basis on each of the log N levels of blocks they meet. The H²
// form (Hackbusch, Khoromskij and Sauter 2000; Börm, "Efficient numerical methods for
// non-local operators", 2010, ch. 6) keeps instead
//
//   A_b ≈ Q_τ S_b P_σᵀ,
//
// with row bases Q_τ (|τ| × k_τ) and column bases P_σ (g|σ| × k_σ, the g densities' rows
// d·|σ| + c as in the H-matrix's V) shared by every block of the cluster, and nested: for a
// cluster t with children t₁, t₂, Q_t = diag(Q_t₁, Q_t₂) T_t with a transfer matrix T_t
// ((k_t₁ + k_t₂) × k_t), so only the leaves store bases of their panels. S_b (k_τ × k_σ)
// is the block's coupling matrix.
//
// Construction from the H-matrix's factors (the algebraic conversion of Börm's ch. 6.5),
// bottom up. The row basis of a cluster t must represent every block whose row cluster τ
// contains t, restricted to the rows of t. Block b contributes, for the error criterion
// ‖A_b − Q_τ S_b P_σᵀ‖_F ≤ ε‖A_b‖_F, the columns
//
//   ω_{b,t} · F_b|_t Rᵀ,     ω_{b,t} = √(|τ|/|t|) / ‖A_b‖_F,
//
// with F_b = U_b, R the triangular factor of V_b (V_bᵀV_b = RᵀR, so F|_t Rᵀ has the Gram
// matrix of A_b|_t), and √(|τ|/|t|) spreading the block's error over the disjoint clusters
// of one level. A leaf's basis is the leading left singular vectors of all those columns;
// an inner cluster's transfer matrix those of the same columns expressed in its children's
// bases, [Q_t₁ᵀ F_b|_t₁; Q_t₂ᵀ F_b|_t₂] Rᵀ. Each cluster drops singular values whose squares
// add up to at most (ε/√L)² for a tree of depth L, so over the levels the restriction to
// the row bases changes each block by at most ε relative; the column side is the same with
// F_b = V_b, R from U_b. The coupling matrices are S_b = (Q_τᵀ U_b)(P_σᵀ V_b)ᵀ, from the
// transformed factors the construction computes anyway.
//
// This class computes the bases, couplings and their sizes, and applies the far field in
// this form; it is what docs/benchmarks.md ("Far field in the H² form") measures the H²
// storage of the Laplace far field with.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/operators/operator_block_generator.hpp"

namespace bemshape::bench {

using bem::ClusterTree;

/// A low-rank block A_b ≈ U Vᵀ of an operator's far field with its factors in double
/// precision: rows [row_begin, row_end) and columns [col_begin, col_end) in tree order,
/// U: o|τ| × k, V: g|σ| × k (row d·|σ| + c for density d).
struct LowRankBlockCopy {
  Eigen::Index row_begin = 0, row_end = 0, col_begin = 0, col_end = 0;
  Eigen::MatrixXd U, V;
};

/// The far field of the operator `generator` serves on `tree` as the H-matrix with factors in
/// double precision holds it (bem::HierarchicalMatrix with HierarchicalMatrixOptions
/// {aca_tolerance, eta, false, false, false}): the admissible blocks of
/// bem::partition_blocks(tree, eta), each approximated by bem::approximate_admissible_block
/// with the rank limit bem::admissible_rank_limit(…, false), in the H-matrix's order (larger
/// blocks first) and without the blocks whose approximation reaches the limit (stored
/// densely there).
std::vector<LowRankBlockCopy> far_field_low_rank_blocks(
    const ClusterTree& tree, const bem::OperatorBlockGenerator& generator, double aca_tolerance,
    double eta);

/// The bases of one side (rows or columns) of the blocks, per cluster of the tree.
struct NestedBasisSide {
  int densities = 1;  ///< rows per panel: 1 for the row side, g for the column side
  /// k_t of every cluster (0 where no block's cluster contains it).
  std::vector<Eigen::Index> rank;
  /// Leaves: the orthonormal basis (g|t| × k_t, row d·|t| + i); inner clusters: the transfer
  /// matrix ((k_t₁ + k_t₂) × k_t) from the children's bases.
  std::vector<Eigen::MatrixXd> basis;

  /// The basis of cluster c in explicit form, g|c| × k_c, by applying the transfer matrices
  /// down to the leaves.
  Eigen::MatrixXd expand(const ClusterTree& tree, int c) const;
};

class NestedClusterBasis {
 public:
  /// Bases for `blocks` (the low-rank blocks of an H-matrix on `tree`, g = `densities` on the
  /// column side), so that each block changes by at most about `tolerance` relative in
  /// Frobenius norm on each side (2·tolerance for both, as a bound).
  NestedClusterBasis(const ClusterTree& tree,
                     const std::vector<LowRankBlockCopy>& blocks, int densities,
                     double tolerance);

  const NestedBasisSide& rows() const { return rows_; }
  const NestedBasisSide& columns() const { return columns_; }
  /// Row and column clusters of block b (indices into the tree), in the order given.
  int row_cluster(std::size_t b) const { return row_cluster_[b]; }
  int column_cluster(std::size_t b) const { return column_cluster_[b]; }
  /// S_b, k_τ × k_σ.
  const Eigen::MatrixXd& coupling(std::size_t b) const { return coupling_[b]; }

  /// y += Σ_b Q_τ S_b P_σᵀ x|_σ over the blocks, for k vectors at once, in tree order: x is
  /// N × g·k (column j·g + d = density d of vector j, as HierarchicalMatrix::multiply_add),
  /// y is N × k; `tree` the tree the bases were built on. The H² product's three steps: the
  /// forward transformation x̂_σ = P_σᵀ x|_σ up the tree (the leaves' bases, then the
  /// transfer matrices: x̂_t = T_tᵀ [x̂_t₁; x̂_t₂]), the couplings ŷ_τ = Σ_b S_b x̂_σ, and the
  /// backward transformation down the tree ([ŷ_t₁; ŷ_t₂] += T_t ŷ_t, y|_t += Q_t ŷ_t at the
  /// leaves). Each basis, transfer and coupling matrix is read once for all k vectors.
  void multiply_add(const ClusterTree& tree, const Eigen::Ref<const Eigen::MatrixXd>& x,
                    Eigen::Ref<Eigen::MatrixXd> y) const;

  /// Numbers stored by the H² form: the leaves' bases (both sides), the transfer matrices
  /// (both sides) and the coupling matrices, k_τ·k_σ each. S_b = (Q_τᵀU_b)(P_σᵀV_b)ᵀ has the
  /// block's H-matrix rank k_b as inner dimension, so it can also be kept as those two
  /// factors, (k_τ + k_σ)·k_b numbers: `factored_coupling_entries` takes the smaller form of
  /// each block.
  struct Storage {
    std::uint64_t leaf_basis_entries = 0, transfer_entries = 0, coupling_entries = 0;
    std::uint64_t factored_coupling_entries = 0;
    std::uint64_t entries() const {
      return leaf_basis_entries + transfer_entries + coupling_entries;
    }
    std::uint64_t entries_with_factored_couplings() const {
      return leaf_basis_entries + transfer_entries + factored_coupling_entries;
    }
  };
  Storage storage() const;

 private:
  NestedBasisSide rows_, columns_;
  std::vector<int> row_cluster_, column_cluster_;
  std::vector<bool> leaf_;                               ///< per cluster: a leaf of the tree
  std::vector<Eigen::Index> block_rank_;                 ///< k_b of each block's H-matrix factors
  std::vector<std::vector<std::size_t>> blocks_of_row_;  ///< per cluster: its blocks as row cluster
  std::vector<Eigen::MatrixXd> coupling_;
};

/// ‖A_b − Q_τ S_b P_σᵀ‖_F / ‖A_b‖_F for A_b = U Vᵀ, bounded as the sum of the two sides'
/// projection errors ‖(I − QQᵀ)A_b‖ + ‖A_b(I − PPᵀ)‖ (computed from the factors without
/// cancellation). Q (|τ| × k) and P (g|σ| × k) explicit and orthonormal.
double nested_basis_error_bound(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v,
                                const Eigen::MatrixXd& q, const Eigen::MatrixXd& p);

}  // namespace bemshape::bench
