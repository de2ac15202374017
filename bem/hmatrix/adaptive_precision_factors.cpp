#include "bem/hmatrix/adaptive_precision_factors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "linalg/mixed_precision_products.hpp"
#include "core/assert.hpp"

namespace bemshape::bem {

namespace {

/// Columns [first, first + count) of x in fixed point: q (x.rows() × count, column-major) and
/// one scale per column.
template <class Int>
void store_fixed_point(const Eigen::MatrixXd& x, Eigen::Index first, Eigen::Index count, Int* q,
                       double* scale) {
  for (Eigen::Index c = 0; c < count; ++c)
    linalg::to_fixed_point<Int>(x.col(first + c), q + c * x.rows(), scale[c]);
}

/// out.col(first + c) = scale[c]·stored(:, c) over rows [begin, begin + count) for the
/// `columns` columns of `rows` rows at `stored`, in double precision (no scale: single
/// precision). Column by column: contiguous reads and writes, which the compiler vectorises.
template <class T>
void widen_columns(const T* stored, Eigen::Index rows, Eigen::Index columns, const double* scale,
                   Eigen::Index first, Eigen::Index begin, Eigen::Index count,
                   Eigen::Ref<Eigen::MatrixXd> out) {
  for (Eigen::Index c = 0; c < columns; ++c) {
    const T* from = stored + c * rows + begin;
    double* to = out.col(first + c).data();
    const double s = scale ? scale[c] : 1.0;
    for (Eigen::Index r = 0; r < count; ++r) to[r] = s * double(from[r]);
  }
}

/// Error of the column pair (u, v) stored with rounding errors eu, ev:
/// ‖ũ ṽᵀ − u vᵀ‖ ≤ eu (‖v‖ + ev) + ‖u‖ ev.
double column_error(double u_norm, double eu, double v_norm, double ev) {
  return eu * (v_norm + ev) + u_norm * ev;
}

}  // namespace

AdaptivePrecisionFactors::AdaptivePrecisionFactors(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v,
                                                   bool fixed_point)
    : rows_(u.rows()), cols_(v.rows()) {
  BEMSHAPE_ASSERT(u.cols() == v.cols(), "low-rank factors: U and V need the same number of columns");
  const Eigen::Index r = u.cols();
  columns_.single = r;
  if (fixed_point && r > 0) {
    // Rounding error of each column pair in 16- and 8-bit fixed point, and their sums over
    // the columns from i on: e16_tail(i) = Σ_{l ≥ i} e16_l (likewise e8_tail).
    Eigen::VectorXd e16_tail = Eigen::VectorXd::Zero(r + 1), e8_tail = Eigen::VectorXd::Zero(r + 1);
    for (Eigen::Index i = r - 1; i >= 0; --i) {
      const double un = u.col(i).norm(), vn = v.col(i).norm();
      double scale = 0.0;
      const double e16 = column_error(un, linalg::to_fixed_point<std::int16_t>(u.col(i), nullptr, scale), vn,
                                      linalg::to_fixed_point<std::int16_t>(v.col(i), nullptr, scale));
      const double e8 = column_error(un, linalg::to_fixed_point<std::int8_t>(u.col(i), nullptr, scale), vn,
                                     linalg::to_fixed_point<std::int8_t>(v.col(i), nullptr, scale));
      e16_tail(i) = e16_tail(i + 1) + e16;
      e8_tail(i) = e8_tail(i + 1) + e8;
    }
    // The split [0, a) single, [a, b) 16-bit, [b, r) 8-bit with the fewest bytes among those
    // whose fixed-point columns add up to at most β: O(r²) candidates, r is a block's rank.
    const double budget = std::ldexp(u.col(0).norm() * v.col(0).norm(), -23);
    Eigen::Index best_bytes = 4 * r;
    for (Eigen::Index a = 0; a <= r; ++a)
      for (Eigen::Index b = a; b <= r; ++b) {
        const double error = (e16_tail(a) - e16_tail(b)) + e8_tail(b);
        const Eigen::Index bytes = 4 * a + 2 * (b - a) + (r - b);
        if (error <= budget && bytes < best_bytes) {
          best_bytes = bytes;
          columns_ = {a, b - a, r - b};
        }
      }
  }
  const Eigen::Index scales = columns_.fixed16 + columns_.fixed8, entries = rows_ + cols_;
  buffer_.resize(std::size_t(8 * 2 * scales + 4 * entries * columns_.single +
                             2 * entries * columns_.fixed16 + entries * columns_.fixed8));
  const auto store = [&](const Eigen::MatrixXd& x, const Factor& f) {
    // The views point into buffer_, which this constructor owns: writing through them is
    // writing the buffer.
    float* single = const_cast<float*>(f.single);
    for (Eigen::Index c = 0; c < columns_.single; ++c)
      for (Eigen::Index r = 0; r < x.rows(); ++r) single[c * x.rows() + r] = float(x(r, c));
    store_fixed_point(x, columns_.single, columns_.fixed16, const_cast<std::int16_t*>(f.fixed16),
                      const_cast<double*>(f.scale16));
    store_fixed_point(x, columns_.single + columns_.fixed16, columns_.fixed8,
                      const_cast<std::int8_t*>(f.fixed8), const_cast<double*>(f.scale8));
  };
  store(u, factor(true));
  store(v, factor(false));
}

AdaptivePrecisionFactors::Factor AdaptivePrecisionFactors::factor(bool u) const {
  const std::byte* base = buffer_.data();
  const Eigen::Index f16 = columns_.fixed16, f8 = columns_.fixed8, a = columns_.single;
  Factor f;
  f.rows = u ? rows_ : cols_;
  f.columns = columns_;
  // Offsets of U's part of each section, then V's (whose sections follow U's).
  const Eigen::Index scales_u = 0, scales_v = 8 * (f16 + f8);
  const Eigen::Index singles = 16 * (f16 + f8), fixed16 = singles + 4 * (rows_ + cols_) * a,
                     fixed8 = fixed16 + 2 * (rows_ + cols_) * f16;
  const Eigen::Index skip = u ? 0 : rows_;  // V's columns follow all of U's in each section
  f.scale16 = reinterpret_cast<const double*>(base + (u ? scales_u : scales_v));
  f.scale8 = f.scale16 + f16;
  f.single = reinterpret_cast<const float*>(base + singles) + skip * a;
  f.fixed16 = reinterpret_cast<const std::int16_t*>(base + fixed16) + skip * f16;
  f.fixed8 = reinterpret_cast<const std::int8_t*>(base + fixed8) + skip * f8;
  return f;
}

void AdaptivePrecisionFactors::Factor::decode(Eigen::Index begin, Eigen::Index count,
                                              Eigen::Ref<Eigen::MatrixXd> out) const {
  widen_columns(single, rows, columns.single, nullptr, 0, begin, count, out);
  widen_columns(fixed16, rows, columns.fixed16, scale16, columns.single, begin, count, out);
  widen_columns(fixed8, rows, columns.fixed8, scale8, columns.single + columns.fixed16, begin, count, out);
}

void AdaptivePrecisionFactors::Factor::add_product(const Eigen::Ref<const Eigen::MatrixXd>& t,
                                                   Eigen::Ref<Eigen::MatrixXd> out) const {
  const Eigen::Index a = columns.single, b = a + columns.fixed16;
  linalg::add_scaled_columns(single, rows, rows, a, nullptr, t.topRows(a), out);
  linalg::add_scaled_columns(fixed16, rows, rows, columns.fixed16, scale16, t.middleRows(a, columns.fixed16), out);
  linalg::add_scaled_columns(fixed8, rows, rows, columns.fixed8, scale8, t.middleRows(b, columns.fixed8), out);
}

void AdaptivePrecisionFactors::Factor::add_transpose_product(const Eigen::Ref<const Eigen::MatrixXd>& x,
                                                             Eigen::Ref<Eigen::MatrixXd> t) const {
  const Eigen::Index a = columns.single, b = a + columns.fixed16;
  linalg::add_scaled_column_dots(single, rows, rows, a, nullptr, x, t.topRows(a));
  linalg::add_scaled_column_dots(fixed16, rows, rows, columns.fixed16, scale16, x, t.middleRows(a, columns.fixed16));
  linalg::add_scaled_column_dots(fixed8, rows, rows, columns.fixed8, scale8, x, t.middleRows(b, columns.fixed8));
}

void AdaptivePrecisionFactors::multiply_v_transpose(const Eigen::Ref<const Eigen::MatrixXd>& x,
                                                    Eigen::MatrixXd& t) const {
  BEMSHAPE_ASSERT(x.rows() == cols_, "low-rank product: x must have one row per column of the block");
  t.setZero(rank(), x.cols());
  factor(false).add_transpose_product(x, t);
}

void AdaptivePrecisionFactors::add_u_product(const Eigen::Ref<const Eigen::MatrixXd>& t,
                                             Eigen::Ref<Eigen::MatrixXd> out) const {
  BEMSHAPE_ASSERT(t.rows() == rank() && out.rows() == rows_ && out.cols() == t.cols(),
                  "low-rank product: t must be rank × k and out rows × k");
  factor(true).add_product(t, out);
}

Eigen::MatrixXd AdaptivePrecisionFactors::u_rows(Eigen::Index begin, Eigen::Index count) const {
  Eigen::MatrixXd out(count, rank());
  factor(true).decode(begin, count, out);
  return out;
}

Eigen::MatrixXd AdaptivePrecisionFactors::v_rows(Eigen::Index begin, Eigen::Index count) const {
  Eigen::MatrixXd out(count, rank());
  factor(false).decode(begin, count, out);
  return out;
}

std::uint64_t AdaptivePrecisionFactors::bytes() const { return buffer_.size(); }

}  // namespace bemshape::bem
