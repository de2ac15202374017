#pragma once
// Low-rank factors A ≈ U Vᵀ stored column by column in the narrowest of three formats the
// block's accuracy allows: single precision, or 16- or 8-bit fixed point with one scale per
// column and factor.
//
// After recompression (adaptive_cross_approximation.hpp) U = [σ_1 û_1, …, σ_r û_r] with σ
// decreasing and V orthonormal, so column i weighs σ_i in the block: rounding u_i and v_i
// to relative accuracy δ changes the block by about σ_i·δ. Single precision rounds every
// entry to 2^−24 relative, so the leading column alone is stored with an error up to
//   β = 2^−23 ‖u_1‖ ‖v_1‖   (2^−24 for each factor),
// and the columns whose σ_i is several decades below σ_1 carry far more digits than that
// error leaves meaningful. Those are stored in b-bit fixed point (b = 16 or 8: q =
// round(x/s), s = max|x|/(2^{b−1} − 1)), each column pair with its measured rounding error
//   e_i = ‖ũ_i ṽ_iᵀ − u_i v_iᵀ‖_F ≤ ‖ũ_i − u_i‖ ‖ṽ_i‖ + ‖u_i‖ ‖ṽ_i − v_i‖,
// under the condition Σ_{fixed-point i} e_i ≤ β. The fixed-point columns thus change the
// block by at most β: the stored block's error is at most twice the bound of single
// precision alone (whose effect on products, about 4e−7 relative,
// HierarchicalMatrixOptions documents).
//
// The columns are kept in three contiguous ranges — [0, a) single precision, [a, b) 16-bit,
// [b, r) 8-bit — and (a, b) is the split with the fewest bytes whose errors add up to at
// most β (all r² splits are tried; r is a block's rank). Since the σ_i decrease, the tail
// goes to 8 bits and the middle to 16. On Laplace blocks at ε = 1e−8 that is about half
// the columns (docs/benchmarks.md has the measured memory). Products are computed in
// double precision; each stored column is widened in registers as the product reads it
// (linalg/mixed_precision_products.hpp), and no double copy is held.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace bemshape::bem {

class AdaptivePrecisionFactors {
 public:
  /// Columns per format.
  struct Columns {
    Eigen::Index single = 0, fixed16 = 0, fixed8 = 0;
  };

  AdaptivePrecisionFactors() = default;
  /// U (m×r) and V (n×r) with U's column norms decreasing (recompress's output, V
  /// orthonormal; any factors are stored correctly, the rule only then saves most). With
  /// `fixed_point` false every column is kept in single precision.
  AdaptivePrecisionFactors(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool fixed_point = true);

  Eigen::Index rows() const { return rows_; }
  Eigen::Index cols() const { return cols_; }
  Eigen::Index rank() const { return columns_.single + columns_.fixed16 + columns_.fixed8; }
  const Columns& columns() const { return columns_; }

  /// t = Vᵀ x (rank × k) for x of cols() rows.
  void multiply_v_transpose(const Eigen::Ref<const Eigen::MatrixXd>& x, Eigen::MatrixXd& t) const;
  /// out += U t for t of rank() rows (out: rows() × t.cols()).
  void add_u_product(const Eigen::Ref<const Eigen::MatrixXd>& t, Eigen::Ref<Eigen::MatrixXd> out) const;

  /// Rows [begin, begin + count) of the stored U or V, in double precision.
  Eigen::MatrixXd u_rows(Eigen::Index begin, Eigen::Index count) const;
  Eigen::MatrixXd v_rows(Eigen::Index begin, Eigen::Index count) const;

  /// Bytes of the stored factors and their scales.
  std::uint64_t bytes() const;
  /// Entries of U and V, (rows + cols)·rank.
  std::uint64_t entries() const { return std::uint64_t(rows_ + cols_) * std::uint64_t(rank()); }

 private:
  /// One factor (U or V), viewed in the buffer: its columns in the three formats (column-major,
  /// `rows` rows each) and the fixed-point scales.
  struct Factor {
    Eigen::Index rows = 0;
    Columns columns;
    const float* single = nullptr;
    const std::int16_t* fixed16 = nullptr;
    const std::int8_t* fixed8 = nullptr;
    const double* scale16 = nullptr;
    const double* scale8 = nullptr;
    /// Rows [begin, begin + count) in double precision (count × rank).
    void decode(Eigen::Index begin, Eigen::Index count, Eigen::Ref<Eigen::MatrixXd> out) const;
    /// out += F t (t: rank × k) and t += Fᵀ x (x: rows × k), in double arithmetic
    /// (linalg/mixed_precision_products.hpp).
    void add_product(const Eigen::Ref<const Eigen::MatrixXd>& t, Eigen::Ref<Eigen::MatrixXd> out) const;
    void add_transpose_product(const Eigen::Ref<const Eigen::MatrixXd>& x, Eigen::Ref<Eigen::MatrixXd> t) const;
  };
  /// The views of U (`u` true) or V into buffer_.
  Factor factor(bool u) const;

  /// Everything in one allocation, by decreasing alignment: the scales (U's 16-bit, U's
  /// 8-bit, V's 16-bit, V's 8-bit), the single-precision columns (U's, V's), the 16-bit
  /// columns, the 8-bit columns. A block holds one heap allocation instead of one per
  /// format and factor: at 10⁵ panels there are 10⁵ blocks and more, and each allocation
  /// costs its own header and alignment padding.
  std::vector<std::byte> buffer_;
  Eigen::Index rows_ = 0, cols_ = 0;
  Columns columns_;
};

}  // namespace bemshape::bem
