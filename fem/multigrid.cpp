#include "fem/multigrid.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/assert.hpp"
#include "core/cancellation.hpp"
#include "core/errors.hpp"

namespace bemshape::fem {
namespace {

/// Power iterations for λmax(diag(A)⁻¹A): the estimate only needs to be within the safety
/// factor of the true value, which 30 steps from a rough start achieve on these stencils.
constexpr int kPowerIterations = 30;
/// The power iteration approaches λmax from below; Chebyshev amplifies eigenmodes above its
/// interval, so the estimate is raised by 15% (and then capped by the Gershgorin bound,
/// which is rigorous).
constexpr double kLambdaSafety = 1.15;

template <int D>
std::array<GridIndex, D> multi_index(GridIndex index, const std::array<GridIndex, D>& extent) {
  std::array<GridIndex, D> p{};
  for (int d = 0; d < D; ++d) {
    p[d] = index % extent[d];
    index /= extent[d];
  }
  return p;
}

template <int D>
GridIndex node_number(const std::array<GridIndex, D>& p, const std::array<GridIndex, D>& cells) {
  GridIndex index = 0;
  for (int d = D - 1; d >= 0; --d)
    index = index * (cells[d] + 1) + p[d];
  return index;
}

template <int D>
std::array<GridIndex, D> interior_extent(const std::array<GridIndex, D>& cells) {
  std::array<GridIndex, D> e{};
  for (int d = 0; d < D; ++d)
    e[d] = cells[d] - 1;
  return e;
}

template <int D>
GridIndex count(const std::array<GridIndex, D>& extent) {
  GridIndex n = 1;
  for (int d = 0; d < D; ++d)
    n *= extent[d];
  return n;
}

}  // namespace

template <int D>
void prolongate_add(const std::array<GridIndex, D>& fine_cells, const Eigen::MatrixXd& coarse,
                    Eigen::MatrixXd& fine) {
  std::array<GridIndex, D> coarse_cells{};
  for (int d = 0; d < D; ++d)
    coarse_cells[d] = fine_cells[d] / 2;
  const auto extent = interior_extent<D>(fine_cells);
  const GridIndex n = count<D>(extent);
  const Eigen::Index m = fine.cols();
#pragma omp parallel for schedule(static)
  for (GridIndex i = 0; i < n; ++i) {
    auto p = multi_index<D>(i, extent);
    for (int d = 0; d < D; ++d)
      ++p[d];
    const GridIndex target = node_number<D>(p, fine_cells);
    // Per axis: an even fine index coincides with a coarse node, an odd one lies halfway.
    for (int bits = 0; bits < (1 << D); ++bits) {
      std::array<GridIndex, D> c{};
      double weight = 1.0;
      bool used = true;
      for (int d = 0; d < D; ++d) {
        const int b = (bits >> d) & 1;
        if (p[d] % 2 == 0) {
          if (b == 1) {
            used = false;
            break;
          }
          c[d] = p[d] / 2;
        } else {
          c[d] = (p[d] - 1) / 2 + b;
          weight *= 0.5;
        }
      }
      if (!used)
        continue;
      const GridIndex source = node_number<D>(c, coarse_cells);
      for (Eigen::Index j = 0; j < m; ++j)
        fine(target, j) += weight * coarse(source, j);
    }
  }
}

template <int D>
void restrict_transpose(const std::array<GridIndex, D>& fine_cells, const Eigen::MatrixXd& fine,
                        Eigen::MatrixXd& coarse) {
  std::array<GridIndex, D> coarse_cells{};
  GridIndex coarse_nodes = 1;
  for (int d = 0; d < D; ++d) {
    coarse_cells[d] = fine_cells[d] / 2;
    coarse_nodes *= coarse_cells[d] + 1;
  }
  const Eigen::Index m = fine.cols();
  coarse.setZero(coarse_nodes, m);
  const auto extent = interior_extent<D>(coarse_cells);
  const GridIndex n = count<D>(extent);
  constexpr int kStencil = D == 2 ? 9 : 27;
#pragma omp parallel for schedule(static)
  for (GridIndex i = 0; i < n; ++i) {
    auto c = multi_index<D>(i, extent);
    for (int d = 0; d < D; ++d)
      ++c[d];
    const GridIndex target = node_number<D>(c, coarse_cells);
    for (int s = 0; s < kStencil; ++s) {
      std::array<GridIndex, D> p{};
      double weight = 1.0;
      int rest = s;
      for (int d = 0; d < D; ++d) {
        const int o = rest % 3 - 1;
        rest /= 3;
        p[d] = 2 * c[d] + o;
        if (o != 0)
          weight *= 0.5;
      }
      const GridIndex source = node_number<D>(p, fine_cells);
      for (Eigen::Index j = 0; j < m; ++j)
        coarse(target, j) += weight * fine(source, j);
    }
  }
}

template <int D>
Multigrid<D>::Multigrid(ShapeFeatureOperator<D> fine, const MultigridOptions& options)
    : options_(options) {
  BEMSHAPE_ASSERT(options_.smoothing_degree >= 1, "Chebyshev degree must be positive");
  BEMSHAPE_ASSERT(options_.smoothing_range > 1.0, "smoothing range must exceed 1");
  levels_.push_back(Level{std::move(fine), {}, 0.0, {}, {}, {}, {}, {}});
  while (levels_.back().op.can_coarsen() &&
         levels_.back().op.num_nodes() > options_.max_coarse_nodes) {
    auto coarse = levels_.back().op.coarsened();
    levels_.push_back(Level{std::move(coarse), {}, 0.0, {}, {}, {}, {}, {}});
  }
  for (auto& level : levels_) {
    throw_if_cancelled();
    const auto& op = level.op;
    Eigen::VectorXd diag = op.diagonal();
    level.inverse_diagonal.resize(op.num_nodes());
    for (GridIndex i = 0; i < op.num_nodes(); ++i)
      level.inverse_diagonal[i] = op.is_boundary_node(i) ? 0.0 : 1.0 / diag[i];
    if (&level == &levels_.back())
      break;
    // Power iteration on diag(A)⁻¹A from a deterministic, non-smooth start vector.
    Eigen::MatrixXd v(op.num_nodes(), 1), w;
    for (GridIndex i = 0; i < op.num_nodes(); ++i)
      v(i, 0) = level.inverse_diagonal[i] == 0.0 ? 0.0 : 1.0 + 0.5 * std::sin(12.9898 * i);
    double estimate = 0.0;
    for (int k = 0; k < kPowerIterations; ++k) {
      throw_if_cancelled();
      v /= v.norm();
      op.apply(v, w);
      w.array().colwise() *= level.inverse_diagonal.array();
      estimate = w.norm();
      std::swap(v, w);
    }
    level.lambda_max = std::min(op.jacobi_gershgorin_bound(), kLambdaSafety * estimate);
  }
  // Dense Cholesky of the coarsest level on its interior nodes.
  const auto& coarsest = levels_.back().op;
  for (GridIndex i = 0; i < coarsest.num_nodes(); ++i)
    if (!coarsest.is_boundary_node(i))
      coarse_unknowns_.push_back(i);
  const auto n = static_cast<Eigen::Index>(coarse_unknowns_.size());
  Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(coarsest.num_nodes(), n), image;
  for (Eigen::Index j = 0; j < n; ++j)
    unit(coarse_unknowns_[j], j) = 1.0;
  coarsest.apply(unit, image);
  Eigen::MatrixXd dense(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    dense.row(i) = image.row(coarse_unknowns_[i]);
  coarse_factor_.compute(dense);
  if (coarse_factor_.info() != Eigen::Success)
    throw NumericalError("multigrid: the coarsest shape-feature operator (" + std::to_string(n) +
                         " unknowns) is not positive definite; check a > 0 and h0 > 0");
}

template <int D>
void Multigrid<D>::smooth(const Level& level, bool zero_initial_guess, bool want_residual) const {
  const double lambda_max = level.lambda_max;
  const double lambda_min = lambda_max / options_.smoothing_range;
  const double theta = 0.5 * (lambda_max + lambda_min), delta = 0.5 * (lambda_max - lambda_min);
  const double sigma = theta / delta;
  double rho = 1.0 / sigma;
  const auto& inv = level.inverse_diagonal.array();
  if (zero_initial_guess) {
    level.x.setZero(level.b.rows(), level.b.cols());
    level.r = level.b;
  } else {
    level.op.apply(level.x, level.t);
    level.r = level.b - level.t;
  }
  level.d = (level.r.array().colwise() * inv).matrix() / theta;
  const int degree = options_.smoothing_degree;
  for (int k = 1; k <= degree; ++k) {
    level.x += level.d;
    if (k == degree && !want_residual)
      break;
    level.op.apply(level.d, level.t);
    level.r -= level.t;
    if (k == degree)
      break;
    const double rho_next = 1.0 / (2.0 * sigma - rho);
    level.d = rho_next * rho * level.d +
              (2.0 * rho_next / delta) * (level.r.array().colwise() * inv).matrix();
    rho = rho_next;
  }
}

template <int D>
void Multigrid<D>::solve_coarsest(const Level& level) const {
  const auto n = static_cast<Eigen::Index>(coarse_unknowns_.size());
  level.x.setZero(level.b.rows(), level.b.cols());
  Eigen::MatrixXd rhs(n, level.b.cols());
  for (Eigen::Index i = 0; i < n; ++i)
    rhs.row(i) = level.b.row(coarse_unknowns_[i]);
  const Eigen::MatrixXd solution = coarse_factor_.solve(rhs);
  for (Eigen::Index i = 0; i < n; ++i)
    level.x.row(coarse_unknowns_[i]) = solution.row(i);
}

template <int D>
void Multigrid<D>::cycle(int index) const {
  const Level& level = levels_[index];
  if (index + 1 == num_levels()) {
    solve_coarsest(level);
    return;
  }
  const Level& next = levels_[index + 1];
  smooth(level, /*zero_initial_guess=*/true, /*want_residual=*/true);
  restrict_transpose<D>(level.op.cells(), level.r, next.b);
  cycle(index + 1);
  prolongate_add<D>(level.op.cells(), next.x, level.x);
  smooth(level, /*zero_initial_guess=*/false, /*want_residual=*/false);
}

template <int D>
void Multigrid<D>::apply(const Eigen::MatrixXd& r, Eigen::MatrixXd& z) const {
  levels_.front().b = r;
  cycle(0);
  z = levels_.front().x;
}

template class Multigrid<2>;
template class Multigrid<3>;
template void prolongate_add<2>(const std::array<GridIndex, 2>&, const Eigen::MatrixXd&,
                                Eigen::MatrixXd&);
template void prolongate_add<3>(const std::array<GridIndex, 3>&, const Eigen::MatrixXd&,
                                Eigen::MatrixXd&);
template void restrict_transpose<2>(const std::array<GridIndex, 2>&, const Eigen::MatrixXd&,
                                    Eigen::MatrixXd&);
template void restrict_transpose<3>(const std::array<GridIndex, 3>&, const Eigen::MatrixXd&,
                                    Eigen::MatrixXd&);

}  // namespace bemshape::fem
