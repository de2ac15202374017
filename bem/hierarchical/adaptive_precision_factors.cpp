#include "bem/hierarchical/adaptive_precision_factors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/assert.hpp"

namespace bemshape::bem {

namespace {

/// Rows converted to double per step of a product: the chunk stays in the first-level cache.
constexpr Eigen::Index kConvertedRows = 128;

/// x in fixed point: q_r = round(x_r/s), s = max|x|/(2^{b−1} − 1), b the width of Int. Writes q
/// (if not null) and s; returns the rounding error ‖x − s q‖ (0 for a zero column).
template <class Int>
double to_fixed_point(const Eigen::Ref<const Eigen::VectorXd>& x, Int* q, double& scale) {
  const double largest = x.cwiseAbs().maxCoeff();
  scale = largest / double(std::numeric_limits<Int>::max());
  if (!(scale > 0.0)) {
    if (q) std::fill(q, q + x.size(), Int(0));
    scale = 0.0;
    return 0.0;
  }
  double error2 = 0.0;
  for (Eigen::Index r = 0; r < x.size(); ++r) {
    const double level = std::nearbyint(x(r) / scale);
    if (q) q[r] = static_cast<Int>(level);
    const double e = x(r) - scale * level;
    error2 += e * e;
  }
  return std::sqrt(error2);
}

/// Columns [first, first + q.cols()) of x in fixed point: q and one scale per column.
template <class Int>
void store_fixed_point(const Eigen::MatrixXd& x, Eigen::Index first,
                       Eigen::Matrix<Int, Eigen::Dynamic, Eigen::Dynamic>& q, Eigen::VectorXd& scale) {
  scale.resize(q.cols());
  for (Eigen::Index c = 0; c < q.cols(); ++c) to_fixed_point<Int>(x.col(first + c), q.col(c).data(), scale(c));
}

/// out.col(first + c) = scale(c)·stored.col(c) over rows [begin, begin + count), in double
/// precision (no scale: single precision). Column by column: contiguous reads and writes,
/// which the compiler vectorises.
template <class T>
void widen_columns(const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>& stored,
                   const Eigen::VectorXd* scale, Eigen::Index first, Eigen::Index begin,
                   Eigen::Index count, Eigen::Ref<Eigen::MatrixXd> out) {
  for (Eigen::Index c = 0; c < stored.cols(); ++c) {
    const T* from = stored.col(c).data() + begin;
    double* to = out.col(first + c).data();
    const double s = scale ? (*scale)(c) : 1.0;
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
      const double e16 = column_error(un, to_fixed_point<std::int16_t>(u.col(i), nullptr, scale), vn,
                                      to_fixed_point<std::int16_t>(v.col(i), nullptr, scale));
      const double e8 = column_error(un, to_fixed_point<std::int8_t>(u.col(i), nullptr, scale), vn,
                                     to_fixed_point<std::int8_t>(v.col(i), nullptr, scale));
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
  const auto store = [&](const Eigen::MatrixXd& x, Factor& f) {
    f.single = x.leftCols(columns_.single).cast<float>();
    f.fixed16.resize(x.rows(), columns_.fixed16);
    store_fixed_point(x, columns_.single, f.fixed16, f.scale16);
    f.fixed8.resize(x.rows(), columns_.fixed8);
    store_fixed_point(x, columns_.single + columns_.fixed16, f.fixed8, f.scale8);
  };
  store(u, u_);
  store(v, v_);
}

void AdaptivePrecisionFactors::Factor::decode(Eigen::Index begin, Eigen::Index count,
                                              Eigen::Ref<Eigen::MatrixXd> out) const {
  widen_columns(single, nullptr, 0, begin, count, out);
  widen_columns(fixed16, &scale16, single.cols(), begin, count, out);
  widen_columns(fixed8, &scale8, single.cols() + fixed16.cols(), begin, count, out);
}

std::uint64_t AdaptivePrecisionFactors::Factor::bytes() const {
  return 4 * std::uint64_t(single.size()) + 2 * std::uint64_t(fixed16.size()) +
         std::uint64_t(fixed8.size()) + 8 * std::uint64_t(scale16.size() + scale8.size());
}

void AdaptivePrecisionFactors::multiply_v_transpose(const Eigen::Ref<const Eigen::MatrixXd>& x,
                                                    Eigen::MatrixXd& t, Eigen::MatrixXd& chunk) const {
  BEMSHAPE_ASSERT(x.rows() == cols_, "low-rank product: x must have one row per column of the block");
  t.setZero(rank(), x.cols());
  for (Eigen::Index i = 0; i < cols_; i += kConvertedRows) {
    const Eigen::Index m = std::min(kConvertedRows, cols_ - i);
    chunk.resize(m, rank());
    v_.decode(i, m, chunk);
    t.noalias() += chunk.transpose() * x.middleRows(i, m);
  }
}

void AdaptivePrecisionFactors::add_u_product(const Eigen::Ref<const Eigen::MatrixXd>& t,
                                             Eigen::Ref<Eigen::MatrixXd> out,
                                             Eigen::MatrixXd& chunk) const {
  BEMSHAPE_ASSERT(t.rows() == rank() && out.rows() == rows_ && out.cols() == t.cols(),
                  "low-rank product: t must be rank × k and out rows × k");
  for (Eigen::Index i = 0; i < rows_; i += kConvertedRows) {
    const Eigen::Index m = std::min(kConvertedRows, rows_ - i);
    chunk.resize(m, rank());
    u_.decode(i, m, chunk);
    out.middleRows(i, m).noalias() += chunk * t;
  }
}

Eigen::MatrixXd AdaptivePrecisionFactors::u_rows(Eigen::Index begin, Eigen::Index count) const {
  Eigen::MatrixXd out(count, rank());
  u_.decode(begin, count, out);
  return out;
}

Eigen::MatrixXd AdaptivePrecisionFactors::v_rows(Eigen::Index begin, Eigen::Index count) const {
  Eigen::MatrixXd out(count, rank());
  v_.decode(begin, count, out);
  return out;
}

std::uint64_t AdaptivePrecisionFactors::bytes() const { return u_.bytes() + v_.bytes(); }

}  // namespace bemshape::bem
