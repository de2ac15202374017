#pragma once
// Hierarchical matrix (H-matrix) of a boundary operator A acting on g densities on the same
// panels, A: (x_1, …, x_g) ↦ Σ_d A_d x_d (N test panels × g·N unknowns), over a block
// partition of a cluster tree (bem/hmatrix/block_partition.hpp): admissible blocks are
// low-rank products from adaptive cross approximation with relative tolerance ε
// (`aca_tolerance`), the others are dense. All indices are tree positions
// (ClusterTree::permutation maps them to mesh faces).
//
// The blocks are computed independently (in parallel) from an OperatorBlockGenerator — the
// same Galerkin entries as the dense path — so each block, and hence the whole matrix, is the
// same whatever the number of threads. The product sums per-thread partial results in thread
// order with a static schedule: bit-identical for a given thread count.

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "bem/hmatrix/adaptive_cross_approximation.hpp"
#include "bem/hmatrix/adaptive_precision_factors.hpp"
#include "bem/hmatrix/block_partition.hpp"
#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/operators/operator_block_generator.hpp"
#include "core/progress.hpp"

namespace bemshape::bem {

struct HierarchicalMatrixOptions {
  /// ε of the cross approximation (relative Frobenius error per block). A couple of digits
  /// below the Krylov tolerance, so the compression does not limit the solve.
  double aca_tolerance = 1e-8;
  /// η of the admissibility condition min(diam τ, diam σ) ≤ η·dist(τ, σ).
  double eta = kDefaultAdmissibility;
  /// Store the low-rank factors U, V in single precision (half the memory of the far field).
  /// Rounding them (unit roundoff 2^−24 ≈ 6e−8) perturbs the product by about 4e−7 relative
  /// (measured on a sphere of 2000 panels at ε = 1e−8, tests/bem/hmatrix): above ε,
  /// below a Krylov tolerance of 1e−6. Products are still computed in double precision.
  bool single_precision_factors = false;
  /// Store the dense (near-field) blocks in single precision too (half their memory).
  /// Rounding an entry changes it by at most 6e−8 relative, less than the factors' effect;
  /// products are computed in double precision.
  bool single_precision_near_field = false;
  /// With single_precision_factors: the columns of small singular value in 16- or 8-bit
  /// fixed point where their rounding stays within that of the leading column in single
  /// precision (bem/hmatrix/adaptive_precision_factors.hpp): the block's storage error
  /// at most doubles, its bytes drop by a third or more.
  bool fixed_point_columns = true;
};

/// The largest rank worth finding for an admissible block of rows × cols entries: where U
/// and V would hold as many entries as the block (`narrow`: 1.5 times that, for factors in
/// the narrow formats of AdaptivePrecisionFactors against a single-precision block).
Eigen::Index admissible_rank_limit(Eigen::Index rows, Eigen::Index cols, bool narrow);

/// The cross approximation of the admissible block (rows [row_begin, row_end), columns
/// [col_begin, col_end) in tree order, o·|τ| × g·|σ| entries) the way the H-matrix computes
/// it: blocks of at most 64·128 entries (any shape) are filled whole first (into `filled`,
/// otherwise left empty) and ACA reads them. Nothing if the rank reaches `max_rank`.
/// Deterministic: the same block gives the same factors every time, whatever the thread.
std::optional<LowRankBlock> approximate_admissible_block(
    const OperatorBlockGenerator& generator, Eigen::Index row_begin, Eigen::Index row_end,
    Eigen::Index col_begin, Eigen::Index col_end, double epsilon, Eigen::Index max_rank,
    Eigen::MatrixXd& filled);

/// Storage statistics.
struct HierarchicalMatrixStats {
  std::uint64_t dense_entries = 0;     ///< entries of the dense (near-field) blocks
  std::uint64_t dense_bytes = 0;       ///< their storage: 4 or 8 bytes per entry
  std::uint64_t low_rank_entries = 0;  ///< entries of the U and V factors
  std::uint64_t low_rank_bytes = 0;    ///< their storage: 1, 2, 4 or 8 bytes per entry
  /// Columns of the low-rank factors in single precision, 16- and 8-bit fixed point
  /// (AdaptivePrecisionFactors; all zero when the factors are in double precision).
  std::uint64_t single_columns = 0, fixed16_columns = 0, fixed8_columns = 0;
  std::uint64_t full_entries = 0;      ///< N·g·N, what a dense matrix would hold
  Eigen::Index max_rank = 0;
  std::size_t admissible_blocks = 0, dense_blocks = 0;
  /// Thread-seconds spent computing the dense blocks (the near field) and the low-rank blocks
  /// (ACA and recompression: the far field), summed over threads [s].
  double dense_seconds = 0.0, low_rank_seconds = 0.0;
  std::uint64_t bytes() const { return dense_bytes + low_rank_bytes; }
  /// Stored entries over the dense matrix's entries.
  double compression() const {
    return full_entries ? double(dense_entries + low_rank_entries) / double(full_entries) : 0.0;
  }
};

/// Rows [begin, begin + n) of k vectors of g densities, x: #elements × g·k (column j·g + d =
/// density d of vector j, the layout of HierarchicalMatrix::multiply_add), stacked density by
/// density as the factors' rows are: g·n × k, row d·n + c, column j.
Eigen::MatrixXd gather_densities(const Eigen::Ref<const Eigen::MatrixXd>& x, int g,
                                 Eigen::Index begin, Eigen::Index n);

class HierarchicalMatrix {
 public:
  /// A square operator on the elements of `tree`.
  HierarchicalMatrix(const ClusterTree& tree, const OperatorBlockGenerator& generator,
                     const HierarchicalMatrixOptions& options = {},
                     const ProgressCallback& progress = {});
  /// An operator from the elements of `col_tree` to those of `row_tree`.
  HierarchicalMatrix(const ClusterTree& row_tree, const ClusterTree& col_tree,
                     const OperatorBlockGenerator& generator,
                     const HierarchicalMatrixOptions& options = {},
                     const ProgressCallback& progress = {});
  /// The blocks of `partition` only (options.eta unused): its admissible blocks low rank
  /// where that pays, its dense blocks dense. With blocks left out (a far field kept in
  /// another form, bem/hmatrix/nested_far_field.hpp) the matrix is that part of A.
  HierarchicalMatrix(const ClusterTree& row_tree, const ClusterTree& col_tree,
                     const BlockPartition& partition, const OperatorBlockGenerator& generator,
                     const HierarchicalMatrixOptions& options = {},
                     const ProgressCallback& progress = {});

  Eigen::Index rows() const { return rows_; }
  int densities() const { return densities_; }
  int outputs() const { return outputs_; }
  const HierarchicalMatrixStats& stats() const { return stats_; }

  /// y += A x for k vectors at once, in tree order: x is #cols × g·k (column j·g + d =
  /// density d of vector j), y is #rows × o·k (column j·o + o' = output o' of vector j).
  /// Each block's storage is read once for all k vectors.
  void multiply_add(const Eigen::Ref<const Eigen::MatrixXd>& x, Eigen::Ref<Eigen::MatrixXd> y) const;

  /// The diagonal blocks A_d(C, C) of the index ranges C = [begin, end) in `ranges` (sorted,
  /// disjoint), low-rank blocks expanded: result[t](r, d·|C| + c) = A_d(begin + r, begin + c).
  /// What a block preconditioner needs.
  std::vector<Eigen::MatrixXd> diagonal_blocks(
      const std::vector<std::pair<Eigen::Index, Eigen::Index>>& ranges) const;

  /// The operator on densities that are constant on groups of elements: with E(j, a) = 1 if
  /// group[j] = a (groups nondecreasing in tree order, e.g. clusters of the tree), A_d E per
  /// block and the Galerkin sums EᵀA_d E. A block meeting few groups keeps A_d E itself,
  /// |τ| × g·|groups met| (a dense block D: D E; a low-rank one: U (EᵀV)ᵀ); a low-rank block
  /// meeting more groups than its rank keeps its U and gets EᵀV. Most blocks meet one or two
  /// groups of the tree's size (hundreds of elements), so a product reads a few numbers per
  /// row of a block where U has tens. O(storage) work once. What a coarse-space correction
  /// needs (bem/solve/cluster_coarse_space.hpp).
  struct GroupedColumns {
    /// How the A_d E kept per block are stored: in double precision, or in 8-bit fixed point
    /// with one scale per column (to_fixed_point: each entry within max|column|/254; the sums
    /// EᵀA_d E are exact either way).
    enum class Storage { exact, fixed8 };
    struct Part {
      bool expanded = false;     ///< A_d E kept (else EᵀV, multiplied by the block's U)
      Eigen::MatrixXd values;    ///< A_d E (expanded, exact) or EᵀV (g·|groups met| × rank)
      std::vector<std::int8_t> fixed8;  ///< A_d E column-major (expanded, fixed8)
      std::vector<double> scale;        ///< fixed8's column scales
    };
    std::vector<Eigen::Index> group;  ///< group of each tree position
    Eigen::Index groups = 0;
    std::vector<Part> parts;  ///< per block, same order as the blocks
    /// sums(a, d·groups + b) = Σ_{group[i] = a, group[j] = b} A_d(i, j) = (Eᵀ A_d E)(a, b).
    Eigen::MatrixXd sums;
    std::uint64_t bytes() const;
  };
  GroupedColumns group_columns(std::vector<Eigen::Index> group, Eigen::Index groups,
                               GroupedColumns::Storage storage) const;

  /// y += A (E x) for k vectors of group values at once: x is groups × g·k (column j·g + d =
  /// density d of vector j), y is #rows × k. Reads U of the low-rank blocks kept factored,
  /// none of V.
  void multiply_add_grouped(const GroupedColumns& grouped, const Eigen::Ref<const Eigen::MatrixXd>& x,
                            Eigen::Ref<Eigen::MatrixXd> y) const;

 private:
  struct Block {
    Eigen::Index row_begin = 0, row_end = 0, col_begin = 0, col_end = 0;
    Eigen::MatrixXd dense;  ///< o|τ| × g|σ|, empty for a low-rank block or in single precision
    Eigen::MatrixXf dense_single;  ///< the same in single precision
    LowRankBlock low_rank;  ///< U: o|τ|×k, V: g|σ|×k (empty when stored in single precision)
    AdaptivePrecisionFactors factors;  ///< the same factors in single precision or narrower
    bool is_low_rank = false;
    /// The block is stored in single precision or narrower: factors (rank may be 0) or
    /// dense_single.
    bool single_precision = false;
  };
  /// The entries of a dense block in double precision, whichever way it is stored.
  static Eigen::MatrixXd dense_entries(const Block& b) {
    return b.single_precision ? Eigen::MatrixXd(b.dense_single.cast<double>()) : b.dense;
  }

  Eigen::Index rows_ = 0, cols_ = 0;
  int densities_ = 1, outputs_ = 1;
  std::vector<Block> blocks_;
  HierarchicalMatrixStats stats_;
};

}  // namespace bemshape::bem
