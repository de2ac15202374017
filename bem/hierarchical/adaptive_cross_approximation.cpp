#include "bem/hierarchical/adaptive_cross_approximation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/QR>
#include <Eigen/SVD>

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

}  // namespace

std::optional<LowRankBlock> adaptive_cross_approximation(Eigen::Index m, Eigen::Index n,
                                                         const RowGenerator& row,
                                                         const ColumnGenerator& column,
                                                         double epsilon, Eigen::Index max_rank) {
  std::vector<Eigen::VectorXd> us, vs;
  std::vector<bool> used(static_cast<size_t>(m), false);
  Eigen::VectorXd r(n), c(m);
  double norm2 = 0.0;  // ‖Σ u_l v_lᵀ‖_F²
  Eigen::Index pivot_row = 0;
  int zero_rows = 0;
  const auto next_unused = [&](Eigen::Index from) {
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Index i = (from + k) % m;
      if (!used[size_t(i)]) return i;
    }
    return Eigen::Index{-1};
  };
  while (true) {
    if (static_cast<Eigen::Index>(us.size()) >= max_rank) return std::nullopt;
    used[size_t(pivot_row)] = true;
    row(pivot_row, r);
    for (size_t l = 0; l < us.size(); ++l) r -= us[l](pivot_row) * vs[l];
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
    Eigen::VectorXd v = r / r(pivot_col);
    column(pivot_col, c);
    for (size_t l = 0; l < us.size(); ++l) c -= vs[l](pivot_col) * us[l];
    // ‖S_k‖² = ‖S_{k−1}‖² + 2 Σ_l (u_l·u)(v_l·v) + ‖u‖²‖v‖²
    for (size_t l = 0; l < us.size(); ++l) norm2 += 2.0 * us[l].dot(c) * vs[l].dot(v);
    const double step = c.norm() * v.norm();
    norm2 += step * step;
    us.push_back(c);
    vs.push_back(std::move(v));
    if (step <= epsilon * std::sqrt(norm2)) {
      // Converged by the estimate: check a few unused rows, spread over the block.
      Eigen::Index failing = -1;
      const double allowed = kCheckFactor * epsilon * std::sqrt(norm2 / double(m));
      for (int t = 1; t <= kCheckRows && failing < 0; ++t) {
        const Eigen::Index i = next_unused((t * m) / (kCheckRows + 1) + pivot_row);
        if (i < 0) break;
        used[size_t(i)] = true;  // checked: its residual is known to be small
        row(i, r);
        for (size_t l = 0; l < us.size(); ++l) r -= us[l](i) * vs[l];
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
  block.U.resize(m, static_cast<Eigen::Index>(us.size()));
  block.V.resize(n, static_cast<Eigen::Index>(vs.size()));
  for (size_t l = 0; l < us.size(); ++l) {
    block.U.col(Eigen::Index(l)) = us[l];
    block.V.col(Eigen::Index(l)) = vs[l];
  }
  return recompress(block, epsilon);
}

LowRankBlock recompress(const LowRankBlock& block, double epsilon) {
  const Eigen::Index k = block.rank();
  if (k == 0) return block;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qu(block.U), qv(block.V);
  const Eigen::Index ku = std::min(k, block.U.rows()), kv = std::min(k, block.V.rows());
  const Eigen::MatrixXd ru = qu.matrixQR().topRows(ku).template triangularView<Eigen::Upper>();
  const Eigen::MatrixXd rv = qv.matrixQR().topRows(kv).template triangularView<Eigen::Upper>();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(ru * rv.transpose(),
                                              Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const double total2 = sigma.squaredNorm();
  Eigen::Index r = sigma.size();
  double tail2 = 0.0;
  while (r > 0 && tail2 + sigma(r - 1) * sigma(r - 1) <= epsilon * epsilon * total2) {
    tail2 += sigma(r - 1) * sigma(r - 1);
    --r;
  }
  LowRankBlock out;
  const Eigen::MatrixXd eu = qu.householderQ() * Eigen::MatrixXd::Identity(block.U.rows(), ku);
  const Eigen::MatrixXd ev = qv.householderQ() * Eigen::MatrixXd::Identity(block.V.rows(), kv);
  out.U = eu * (svd.matrixU().leftCols(r) * sigma.head(r).asDiagonal());
  out.V = ev * svd.matrixV().leftCols(r);
  return out;
}

}  // namespace bemshape::bem
