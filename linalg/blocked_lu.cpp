#include "linalg/blocked_lu.hpp"

#include <algorithm>
#include <utility>

#include "core/assert.hpp"
#include "core/cancellation.hpp"

namespace bemshape::linalg {
namespace {

/// Factorises the panel a(k:N, k:k+w) column by column (unblocked partial pivoting); row
/// swaps touch the panel's columns only.
void factorise_panel(Eigen::MatrixXd& a, Eigen::Index k, Eigen::Index w, Eigen::VectorXi& pivots) {
  const Eigen::Index n = a.rows();
  for (Eigen::Index j = k; j < k + w; ++j) {
    Eigen::Index p = 0;
    const double biggest = a.col(j).segment(j, n - j).cwiseAbs().maxCoeff(&p);
    p += j;
    pivots(j) = static_cast<int>(p);
    if (p != j) a.block(j, k, 1, w).swap(a.block(p, k, 1, w));
    const Eigen::Index below = n - j - 1, right = k + w - j - 1;
    if (biggest != 0.0) a.col(j).segment(j + 1, below) /= a(j, j);
    if (right > 0)
      a.block(j + 1, j + 1, below, right).noalias() -=
          a.col(j).segment(j + 1, below) * a.row(j).segment(j + 1, right);
  }
}

}  // namespace

LuFactors lu_factorise(Eigen::MatrixXd a, const ProgressCallback& progress) {
  BEMSHAPE_ASSERT(a.rows() == a.cols(), "lu_factorise needs a square matrix");
  const Eigen::Index n = a.rows();
  LuFactors f;
  f.pivots.resize(n);
  const double total = double(n) * double(n) * double(n);
  for (Eigen::Index k = 0; k < n; k += kLuPanelColumns) {
    throw_if_cancelled();
    if (total > 0.0) {
      const double left = double(n - k);
      report_progress(progress, "factorise", 1.0 - left * left * left / total);
    }
    const Eigen::Index w = std::min(kLuPanelColumns, n - k), m = n - k - w;
    factorise_panel(a, k, w, f.pivots);
    // The panel's row swaps, applied to the columns left and right of it.
    for (Eigen::Index j = k; j < k + w; ++j) {
      const Eigen::Index p = f.pivots(j);
      if (p == j) continue;
      if (k > 0) a.block(j, 0, 1, k).swap(a.block(p, 0, 1, k));
      if (m > 0) a.block(j, k + w, 1, m).swap(a.block(p, k + w, 1, m));
    }
    if (m == 0) continue;
    a.block(k, k, w, w).triangularView<Eigen::UnitLower>().solveInPlace(a.block(k, k + w, w, m));
    a.bottomRightCorner(m, m).noalias() -= a.block(k + w, k, m, w) * a.block(k, k + w, w, m);
  }
  report_progress(progress, "factorise", 1.0);
  f.lu = std::move(a);
  return f;
}

Eigen::MatrixXd lu_solve(const LuFactors& factors, const Eigen::Ref<const Eigen::MatrixXd>& b) {
  BEMSHAPE_ASSERT(b.rows() == factors.lu.rows(), "lu_solve: right-hand side of the wrong height");
  Eigen::MatrixXd x = b;
  for (Eigen::Index k = 0; k < x.rows(); ++k)
    if (factors.pivots(k) != k) x.row(k).swap(x.row(factors.pivots(k)));
  factors.lu.triangularView<Eigen::UnitLower>().solveInPlace(x);
  factors.lu.triangularView<Eigen::Upper>().solveInPlace(x);
  return x;
}

}  // namespace bemshape::linalg
