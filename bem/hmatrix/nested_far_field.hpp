#pragma once
// The far field of a boundary operator in the H² form, computed from the operator's entries
// without ever holding its H-matrix:
//
//   A_b ≈ Q_τ S_b P_σᵀ   for every admissible block b = (τ, σ),
//
// with nested orthonormal row bases Q_t (|t| × k_t) and column bases P_t (g|t| × k_t, the g
// densities' rows d·|t| + i), stored as the leaves' bases and transfer matrices between
// levels (Q_t = diag(Q_t₁, Q_t₂) T_t), and one coupling matrix S_b per block (the H² form:
// Hackbusch, Khoromskij and Sauter 2000; Börm, "Efficient numerical methods for non-local
// operators", 2010, ch. 6).
//
// Why. The H-matrix stores a pair of factors per block, so each cluster's rows carry a
// basis on every level of blocks they meet; at 10⁶ faces the Laplace row's factors would
// take about 13 GB of the 20 GB a run may use (docs/benchmarks.md, "Fast path at 10⁶
// faces"). Shared nested bases store each cluster's basis once.
//
// Construction, one side at a time, depth first over the cluster tree. Entering a cluster t,
// the cross approximations of t's own blocks on this side are computed (the same ACA and the
// rank limit of the H-matrix with narrow factors, approximate_admissible_block) and held, while t's
// subtree is built, together with those of t's ancestors: only the blocks of the clusters
// on the current path are in memory, never the whole H-matrix. Leaving t (children first),
// its basis (a leaf) or transfer matrix (an inner cluster) is the leading left singular
// vectors of all those blocks' factors restricted to t, expressed in the children's bases,
// each block weighted to unit Frobenius norm and by √(|home|/|t|), |home| the size of the
// block's own cluster on this side (the error criterion ‖A_b − Q_τ S_b P_σᵀ‖_F ≤ ε‖A_b‖_F:
// each cluster drops singular values whose squares add up to at most (tolerance/√L)², L the
// tree's depth, so over the levels the restriction to the bases changes each block by at
// most `tolerance` relative on each side). The row side (F_b = U_b) runs first and keeps
// Q_τᵀU_b for each block; the column side (F_b = V_b) computes every approximation once more,
// bit for bit the same, and forms the coupling S_b = (Q_τᵀU_b)(P_σᵀV_b)ᵀ when P_σ is done.
// The second pass costs a second cross approximation of every block: time, not memory.
//
// Storage. Bases, transfer matrices and couplings in single precision (unit roundoff
// 2^−24 ≈ 6e−8, the precision of the H-matrix's leading factor columns); a coupling is kept
// as the two factors (k_τ × k_b, k_σ × k_b) where that is smaller than k_τ × k_σ. Products
// are computed in double precision.
//
// Blocks whose approximation reaches the rank limit are not in the H² form:
// `uncompressed()` lists them, for the caller to store densely.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "bem/hmatrix/block_partition.hpp"
#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/hmatrix/hierarchical_matrix.hpp"
#include "core/progress.hpp"

namespace bemshape::bem {

struct NestedFarFieldOptions {
  /// ε of each block's cross approximation (relative Frobenius error per block), as the
  /// H-matrix's HierarchicalMatrixOptions::aca_tolerance.
  double aca_tolerance = 1e-8;
  /// What the bases may drop on each side, relative to each block in Frobenius norm; 0 means
  /// aca_tolerance. The stored block is then within about aca_tolerance + 2·basis_tolerance
  /// of A_b, plus the single-precision rounding.
  double basis_tolerance = 0.0;
};

struct NestedFarFieldStats {
  std::size_t blocks = 0;               ///< admissible blocks in the H² form
  std::size_t uncompressed_blocks = 0;  ///< admissible blocks left to the caller (rank limit)
  std::uint64_t leaf_basis_entries = 0, transfer_entries = 0;  ///< both sides
  std::uint64_t coupling_entries = 0;  ///< S_b or its two factors, whichever is smaller
  std::uint64_t bytes = 0;             ///< 4 per entry, plus the per-cluster and per-block headers
  Eigen::Index max_row_rank = 0, max_column_rank = 0;
  /// Wall time of the row and column sides [s] (each computes every block's approximation).
  double row_seconds = 0.0, column_seconds = 0.0;
  /// Thread-seconds of both sides in the blocks' cross approximations and in the bases'
  /// singular value decompositions, and Σ rows²·columns over the latter's inputs.
  double aca_seconds = 0.0, basis_seconds = 0.0;
  std::uint64_t basis_flops = 0;
};

class NestedFarField {
 public:
  /// The H² form of the blocks `admissible` (cluster pairs of `tree`, normally
  /// partition_blocks(tree).admissible) of the operator `generator` (one output, g densities;
  /// indices in tree order). `tree` must outlive the object. Runs in parallel (OpenMP tasks).
  NestedFarField(const ClusterTree& tree, const std::vector<BlockIndex>& admissible,
                 const OperatorBlockGenerator& generator, const NestedFarFieldOptions& options = {},
                 const ProgressCallback& progress = {});

  int densities() const { return densities_; }
  const NestedFarFieldStats& stats() const { return stats_; }
  /// The admissible blocks whose approximation reached admissible_rank_limit: not held here.
  const std::vector<BlockIndex>& uncompressed() const { return uncompressed_; }
  /// The blocks held, in the order block() indexes them.
  const std::vector<BlockIndex>& blocks() const { return blocks_; }

  /// y += A_far x for k vectors at once, in tree order: x is N × g·k (column j·g + d =
  /// density d of vector j, as HierarchicalMatrix::multiply_add), y is N × k. Forward
  /// transformation up the tree (x̂_t = P_tᵀ x|_t), couplings (ŷ_τ += S_b x̂_σ), backward
  /// transformation down the tree (y|_t += Q_t ŷ_t); every stored matrix is read once.
  void multiply_add(const Eigen::Ref<const Eigen::MatrixXd>& x,
                    Eigen::Ref<Eigen::MatrixXd> y) const;

  /// The Galerkin sums of the far field on densities constant on groups of elements:
  /// sums(a, d·groups + c) = Σ_b Σ_{group[i] = a, group[j] = c} A_b,d(i, j) = (Eᵀ A_far,d E)(a, c),
  /// `group` nondecreasing in tree order (HierarchicalMatrix::group_columns has the same
  /// sums for its blocks). From the bases' sums per group, Q_tᵀE|_t and P_tᵀE|_t, formed up
  /// the tree like a forward transformation: O(storage) work, nothing expanded.
  Eigen::MatrixXd grouped_sums(const std::vector<Eigen::Index>& group, Eigen::Index groups) const;

  /// Block b in explicit form, Q_τ S_b P_σᵀ (|τ| × g|σ|, column d·|σ| + c): for tests.
  Eigen::MatrixXd block(std::size_t b) const;

 private:
  struct Side {
    /// k_t per cluster (0 where no block's cluster contains t).
    std::vector<Eigen::Index> rank;
    /// Leaves: the basis (g|t| × k_t); inner clusters: the transfer matrix ((k_t₁ + k_t₂) × k_t).
    std::vector<Eigen::MatrixXf> basis;
  };
  struct Coupling {
    Eigen::MatrixXf left;   ///< S_b (k_τ × k_σ), or its left factor Q_τᵀU_b (k_τ × k_b)
    Eigen::MatrixXf right;  ///< empty, or the right factor P_σᵀV_b (k_σ × k_b)
    /// S_b in double precision, k_τ × k_σ.
    Eigen::MatrixXd matrix() const;
  };
  /// Cluster c's basis in explicit form (g|c| × k_c).
  Eigen::MatrixXd expand(const Side& side, int g, int c) const;

  const ClusterTree* tree_;
  int densities_ = 1;
  Side rows_, columns_;
  std::vector<BlockIndex> blocks_, uncompressed_;
  std::vector<Coupling> couplings_;
  std::vector<std::vector<std::size_t>> blocks_of_row_;  ///< per cluster
  NestedFarFieldStats stats_;
};

}  // namespace bemshape::bem
