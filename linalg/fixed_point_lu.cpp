#include "linalg/fixed_point_lu.hpp"

#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "linalg/mixed_precision_products.hpp"
#include "core/assert.hpp"

namespace bemshape::linalg {
namespace {

constexpr double kLevels = std::numeric_limits<std::int16_t>::max();

/// Entries [begin, end) of column `from` into q in fixed point; returns the scale.
float quantise(const Eigen::MatrixXf& from, Eigen::Index column, Eigen::Index begin, Eigen::Index end,
               std::int16_t* q) {
  if (end <= begin) return 0.0f;
  const float largest = from.col(column).segment(begin, end - begin).cwiseAbs().maxCoeff();
  const float scale = float(double(largest) / kLevels);
  for (Eigen::Index r = begin; r < end; ++r)
    q[r] = scale > 0.0f ? std::int16_t(std::nearbyint(double(from(r, column)) / double(scale))) : 0;
  return scale;
}

/// y_l[r] −= f_l·q[r] for r < rows and the k columns y_l = y + l·ldy.
void subtract_scaled_column(const std::int16_t* q, Eigen::Index rows, const double* f, Eigen::Index k,
                            double* y, Eigen::Index ldy) {
  using namespace mixed_precision_detail;
  const Eigen::Index body = rows - rows % kLanes;
  for (Eigen::Index r = 0; r < body; r += kLanes) {
    const Lanes v = widen(q + r);
    for (Eigen::Index l = 0; l < k; ++l) {
      double* out = y + l * ldy + r;
      store(out, load(out) - f[l] * v);
    }
  }
  for (Eigen::Index r = body; r < rows; ++r)
    for (Eigen::Index l = 0; l < k; ++l) y[l * ldy + r] -= f[l] * double(q[r]);
}

}  // namespace

FixedPointLu::FixedPointLu(const Eigen::MatrixXf& m) : n_(m.rows()) {
  BEMSHAPE_ASSERT(m.rows() == m.cols(), "fixed-point LU: the matrix must be square");
  const Eigen::PartialPivLU<Eigen::MatrixXf> lu(m);
  const Eigen::MatrixXf& f = lu.matrixLU();
  entries_.assign(std::size_t(n_ * n_), 0);
  diagonal_.resize(std::size_t(n_));
  upper_scale_.resize(std::size_t(n_));
  lower_scale_.resize(std::size_t(n_));
  for (Eigen::Index j = 0; j < n_; ++j) {
    std::int16_t* q = entries_.data() + j * n_;
    upper_scale_[size_t(j)] = quantise(f, j, 0, j, q);
    lower_scale_[size_t(j)] = quantise(f, j, j + 1, n_, q);
    diagonal_[size_t(j)] = f(j, j);
  }
  Eigen::VectorXi iota = Eigen::VectorXi::LinSpaced(n_, 0, int(n_ - 1));
  const Eigen::VectorXi order = lu.permutationP() * iota;  // (P x)(i) = x(order(i))
  order_.assign(order.data(), order.data() + n_);
}

void FixedPointLu::solve_in_place(Eigen::Ref<Eigen::MatrixXd> x) const {
  BEMSHAPE_ASSERT(x.rows() == n_, "fixed-point LU: the right-hand sides must have one row per unknown");
  const Eigen::Index k = x.cols();
  Eigen::MatrixXd y(n_, k);
  for (Eigen::Index i = 0; i < n_; ++i) y.row(i) = x.row(order_[size_t(i)]);
  std::vector<double> f(static_cast<std::size_t>(k));
  // L̃ z = P x, column by column (L̃ has a unit diagonal).
  for (Eigen::Index j = 0; j + 1 < n_; ++j) {
    for (Eigen::Index l = 0; l < k; ++l) f[size_t(l)] = double(lower_scale_[size_t(j)]) * y(j, l);
    subtract_scaled_column(entries_.data() + j * n_ + j + 1, n_ - j - 1, f.data(), k,
                           y.data() + j + 1, n_);
  }
  // Ũ x = z, from the last column back.
  for (Eigen::Index j = n_ - 1; j >= 0; --j) {
    for (Eigen::Index l = 0; l < k; ++l) {
      y(j, l) /= double(diagonal_[size_t(j)]);
      f[size_t(l)] = double(upper_scale_[size_t(j)]) * y(j, l);
    }
    subtract_scaled_column(entries_.data() + j * n_, j, f.data(), k, y.data(), n_);
  }
  x = y;
}

std::uint64_t FixedPointLu::bytes() const {
  return 2 * std::uint64_t(entries_.size()) +
         4 * std::uint64_t(diagonal_.size() + upper_scale_.size() + lower_scale_.size() + order_.size());
}

}  // namespace bemshape::linalg
