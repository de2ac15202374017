#include "bem/hmatrix/adaptive_cross_approximation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <Eigen/Eigenvalues>

#include "linalg/gram_orthogonalisation.hpp"

namespace bemshape::bem {
namespace {

/// A residual row whose largest entry is below this fraction of the approximation's norm
/// (or is exactly zero at the start) is treated as zero: the row is already represented,
/// and dividing by its pivot would only amplify rounding.
constexpr double kZeroPivot = 1e-14;

/// Rows tried in a row when the residual rows come out zero before ACA gives up and calls the
/// remaining block zero. Several, because a block can have structurally zero rows (the double
/// layer between coplanar panels vanishes) next to rows that are not.
constexpr int kZeroRowRetries = 8;

/// Partial pivoting sees only the rows and columns it picked, so the usual stopping estimate
/// can be fooled when a part of the block never entered a pivot (seen on point clouds in
/// thin layers: 3e−4 error at ε = 1e−8). Before stopping, this many rows not used yet are
/// checked directly; one whose residual exceeds kCheckFactor × the average row share of the
/// tolerance, ε‖S‖_F/√m, becomes the next pivot.
constexpr int kCheckRows = 3;
constexpr double kCheckFactor = 10.0;

/// recompress, with the Gram matrices UᵀU and VᵀV when the caller has them (else null).
LowRankBlock recompress_with_grams(const LowRankBlock& block, double epsilon, FactorBases bases,
                                   const Eigen::MatrixXd* gram_u, const Eigen::MatrixXd* gram_v);

}  // namespace

std::optional<LowRankBlock> adaptive_cross_approximation(Eigen::Index m, Eigen::Index n,
                                                         const RowGenerator& row,
                                                         const ColumnGenerator& column,
                                                         double epsilon, Eigen::Index max_rank) {
  // The crosses so far, u_l = U(:, l) and v_l = V(:, l) for l < k, in contiguous columns so
  // that each residual update is one matrix-vector product (the rank grows by doubling).
  Eigen::Index capacity = std::min<Eigen::Index>(std::max<Eigen::Index>(max_rank, 1), 16);
  Eigen::MatrixXd U(m, capacity), V(n, capacity);
  Eigen::Index k = 0;
  std::vector<bool> used(static_cast<size_t>(m), false);
  Eigen::VectorXd r(n), c(m);
  // ‖U Vᵀ‖_F², estimated as Σ_l ‖u_l‖²‖v_l‖²: the cross terms 2 Σ_{l<l'} (u_l·u_l')(v_l·v_l')
  // are left out, since updating them would cost two more matrix-vector products per step,
  // as much as the residual updates. It is made exact from the Gram matrices UᵀU and VᵀV
  // whenever the stopping test is about to pass (`exact_norm2`), so the estimate only
  // decides when to look. Recompression reuses the last Gram matrices if no cross was added
  // after them.
  double norm2 = 0.0;
  Eigen::MatrixXd gram_u, gram_v;
  const auto exact_norm2 = [&] {
    const auto u = U.leftCols(k), v = V.leftCols(k);
    gram_u.noalias() = u.transpose() * u;
    gram_v.noalias() = v.transpose() * v;
    return gram_u.cwiseProduct(gram_v).sum();
  };
  Eigen::Index pivot_row = 0;
  int zero_rows = 0;
  const auto next_unused = [&](Eigen::Index from) {
    for (Eigen::Index t = 0; t < m; ++t) {
      const Eigen::Index i = (from + t) % m;
      if (!used[size_t(i)]) return i;
    }
    return Eigen::Index{-1};
  };
  // r = A(i, :) − U(i, :) Vᵀ
  const auto residual_row = [&](Eigen::Index i) {
    row(i, r);
    if (k > 0) r.noalias() -= V.leftCols(k) * U.row(i).head(k).transpose();
  };
  while (true) {
    if (k >= max_rank) return std::nullopt;
    used[size_t(pivot_row)] = true;
    residual_row(pivot_row);
    Eigen::Index pivot_col = 0;
    const double pivot = r.cwiseAbs().maxCoeff(&pivot_col);
    if (!(pivot > kZeroPivot * std::sqrt(norm2)) || pivot == 0.0) {
      // This row is (numerically) represented already; try others before concluding.
      if (++zero_rows > kZeroRowRetries) break;
      // Zero rows come in runs (coplanar panels are neighbours in the tree): jump ahead.
      const Eigen::Index next =
          next_unused(pivot_row + std::max<Eigen::Index>(1, m / (kZeroRowRetries + 1)));
      if (next < 0) break;
      pivot_row = next;
      continue;
    }
    if (k == capacity) {
      capacity = std::min(2 * capacity, max_rank);
      U.conservativeResize(Eigen::NoChange, capacity);
      V.conservativeResize(Eigen::NoChange, capacity);
    }
    V.col(k) = r / r(pivot_col);
    column(pivot_col, c);
    if (k > 0) c.noalias() -= U.leftCols(k) * V.row(pivot_col).head(k).transpose();
    U.col(k) = c;
    const double step = c.norm() * V.col(k).norm();
    norm2 += step * step;
    ++k;
    if (step <= epsilon * std::sqrt(norm2)) norm2 = exact_norm2();
    if (step <= epsilon * std::sqrt(norm2)) {
      // Converged by the estimate: check a few unused rows, spread over the block.
      Eigen::Index failing = -1;
      const double allowed = kCheckFactor * epsilon * std::sqrt(norm2 / double(m));
      for (int t = 1; t <= kCheckRows && failing < 0; ++t) {
        const Eigen::Index i = next_unused((t * m) / (kCheckRows + 1) + pivot_row);
        if (i < 0) break;
        used[size_t(i)] = true;  // checked: its residual is known to be small
        residual_row(i);
        if (r.norm() > allowed) failing = i;
      }
      if (failing < 0) break;
      used[size_t(failing)] = false;
      pivot_row = failing;
      continue;
    }
    // Next pivot: the largest entry of the new column among rows not used yet.
    Eigen::Index best = -1;
    double best_value = -1.0;
    for (Eigen::Index i = 0; i < m; ++i)
      if (!used[size_t(i)] && std::abs(c(i)) > best_value) {
        best_value = std::abs(c(i));
        best = i;
      }
    if (best < 0) break;  // every row used: the approximation is exact
    pivot_row = best;
  }
  LowRankBlock block;
  block.U = U.leftCols(k);
  block.V = V.leftCols(k);
  const bool grams_current = gram_u.rows() == k;
  return recompress_with_grams(block, epsilon, FactorBases::gram_where_conditioned,
                               grams_current ? &gram_u : nullptr,
                               grams_current ? &gram_v : nullptr);
}

namespace {

/// Below this fraction of ‖B‖ the columns of C are B's rounding: nothing to resolve.
constexpr double kRoundingLevel = 1e-15;

/// An orthonormal basis Q of the columns of a factor F (n×k): F = Q R with R upper
/// triangular, and products Q X.
class ColumnBasis {
 public:
  /// Q and R by Householder reflections (R: min(k, n) × k). Always applies.
  static ColumnBasis householder(const Eigen::MatrixXd& f) {
    ColumnBasis b;
    b.qr_.compute(f);
    b.r_ = b.qr_.matrixQR().topRows(std::min(f.cols(), f.rows())).template triangularView<Eigen::Upper>();
    return b;
  }

  /// Q = F R⁻¹ and R from the Cholesky factor of the Gram matrix FᵀF, the columns scaled to
  /// unit norm first: R = R̂ D with D = diag(‖f_l‖) and R̂ᵀR̂ = D⁻¹ FᵀF D⁻¹. Q is then
  /// orthonormal to about u·κ² and Q X = F (R⁻¹ X) carries rounding of about u·κ‖X‖, κ the
  /// condition number of the scaled columns; R̂'s diagonal, the distance of each unit
  /// column from the span of those before it, bounds 1/κ from above to within a factor
  /// of k or so. Applies when every diagonal entry is at least `min_pivot` (and F has no
  /// more columns than rows, no zero column); nothing otherwise.
  static std::optional<ColumnBasis> gram(const Eigen::MatrixXd& f, double min_pivot,
                                         const Eigen::MatrixXd* f_gram = nullptr) {
    const Eigen::Index k = f.cols();
    if (k > f.rows()) return std::nullopt;
    const Eigen::VectorXd norms = f.colwise().norm().transpose();
    if (!(norms.minCoeff() > 0.0)) return std::nullopt;
    const Eigen::VectorXd inverse = norms.cwiseInverse();
    Eigen::MatrixXd gram = f_gram != nullptr ? *f_gram : Eigen::MatrixXd(f.transpose() * f);
    gram = inverse.asDiagonal() * gram * inverse.asDiagonal();
    const Eigen::LLT<Eigen::MatrixXd> cholesky(gram);
    if (cholesky.info() != Eigen::Success) return std::nullopt;
    Eigen::MatrixXd r_scaled = cholesky.matrixU();
    if (!(r_scaled.diagonal().minCoeff() >= min_pivot)) return std::nullopt;
    ColumnBasis b;
    b.f_ = &f;
    b.r_ = r_scaled * norms.asDiagonal();
    return b;
  }

  const Eigen::MatrixXd& r() const { return r_; }

  /// Q X for X of r().rows() rows.
  Eigen::MatrixXd times(const Eigen::MatrixXd& x) const {
    if (f_ != nullptr)
      return *f_ * r_.template triangularView<Eigen::Upper>().solve(x);
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(qr_.rows(), x.cols());
    out.topRows(x.rows()) = x;
    out.applyOnTheLeft(qr_.householderQ());  // on X's columns only: forming Q costs k/r more
    return out;
  }

 private:
  Eigen::HouseholderQR<Eigen::MatrixXd> qr_;
  const Eigen::MatrixXd* f_ = nullptr;  ///< F, for the Gram basis
  Eigen::MatrixXd r_;
};

/// The smallest diagonal of R̂ for which ColumnBasis::gram is taken at tolerance ε: Q's loss
/// of orthogonality (u κ², κ ≲ k/pivot) stays below 1e−6 of the norms the truncation
/// measures, and the rounding of the kept product (u κ) below 1 % of ε.
double gram_min_pivot(Eigen::Index k, double epsilon) {
  constexpr double u = 0.5 * std::numeric_limits<double>::epsilon();
  const double kd = double(std::max<Eigen::Index>(k, 1));
  return std::max(kd * std::sqrt(u / 1e-6), 100.0 * kd * u / epsilon);
}

/// Gram bases of U's and V's columns, if both apply at tolerance ε (from UᵀU and VᵀV where
/// given).
std::optional<std::pair<ColumnBasis, ColumnBasis>> gram_bases(
    const LowRankBlock& block, double epsilon, const Eigen::MatrixXd* gram_u = nullptr,
    const Eigen::MatrixXd* gram_v = nullptr) {
  const double pivot = gram_min_pivot(block.rank(), epsilon);
  auto u = ColumnBasis::gram(block.U, pivot, gram_u);
  if (!u) return std::nullopt;
  auto v = ColumnBasis::gram(block.V, pivot, gram_v);
  if (!v) return std::nullopt;
  return std::pair{std::move(*u), std::move(*v)};
}

}  // namespace

bool recompression_uses_gram_bases(const LowRankBlock& block, double epsilon) {
  return block.rank() > 1 && gram_bases(block, epsilon).has_value();
}

LowRankBlock recompress(const LowRankBlock& block, double epsilon, FactorBases bases) {
  return recompress_with_grams(block, epsilon, bases, nullptr, nullptr);
}

namespace {

LowRankBlock recompress_with_grams(const LowRankBlock& block, double epsilon, FactorBases bases,
                                   const Eigen::MatrixXd* gram_u, const Eigen::MatrixXd* gram_v) {
  const Eigen::Index k = block.rank();
  if (k <= 1) return block;  // rank one is minimal (a zero cross never enters the block)
  // U Vᵀ = Q_u B Q_vᵀ with B = R_u R_vᵀ, from orthonormal bases of U's and V's columns: by
  // their Gram matrices where the columns are well conditioned (ACA's are: each cross
  // vanishes on the pivots before it), two products with U and V instead of two Householder
  // factorisations and their applications; by Householder reflections otherwise.
  auto gram = bases == FactorBases::gram_where_conditioned
                  ? gram_bases(block, epsilon, gram_u, gram_v)
                  : std::nullopt;
  const ColumnBasis bu = gram ? std::move(gram->first) : ColumnBasis::householder(block.U);
  const ColumnBasis bv = gram ? std::move(gram->second) : ColumnBasis::householder(block.V);
  const Eigen::Index ku = bu.r().rows(), kv = bv.r().rows();
  // B W = C with W orthonormal and C's columns orthogonal: the SVD, σᵢ = ‖cᵢ‖.
  Eigen::MatrixXd c = bu.r() * bv.r().transpose();
  Eigen::MatrixXd w = Eigen::MatrixXd::Identity(kv, kv);
  const Eigen::VectorXd all2 = c.colwise().squaredNorm().transpose();
  const double allowed2 = epsilon * epsilon * all2.sum();
  linalg::orthogonalise_columns(c, w, std::max(allowed2, kRoundingLevel * kRoundingLevel * all2.sum()),
                        linalg::resolved_eigenvalues(epsilon));
  const Eigen::VectorXd norms2 = c.colwise().squaredNorm().transpose();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(c.cols()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = Eigen::Index(i);
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index x, Eigen::Index y) { return norms2(x) > norms2(y); });
  // Since W is orthogonal, B = Σᵢ cᵢ wᵢᵀ and dropping a set D of the terms costs exactly
  // Σ_{i∈D} ‖cᵢ‖² in the squared Frobenius norm, whatever W is: the bound holds even where
  // the rotation is not exactly B's singular vectors.
  Eigen::Index r = c.cols();
  double tail2 = 0.0;
  while (r > 0 && tail2 + norms2(order[size_t(r - 1)]) <= allowed2) {
    tail2 += norms2(order[size_t(r - 1)]);
    --r;
  }
  // U' = Q_u C_r and V' = Q_v W_r.
  Eigen::MatrixXd cu(ku, r), cv(kv, r);
  for (Eigen::Index j = 0; j < r; ++j) {
    cu.col(j) = c.col(order[size_t(j)]);
    cv.col(j) = w.col(order[size_t(j)]);
  }
  LowRankBlock out;
  out.U = bu.times(cu);
  out.V = bv.times(cv);
  return out;
}

}  // namespace

}  // namespace bemshape::bem
