#pragma once
// Geometric multigrid V-cycle for the shape-feature operator, used as the preconditioner of
// conjugate gradients.
//
// Hierarchy: the fine operator is halved (ShapeFeatureOperator::coarsened: cells twice as
// large, reaction coefficient α(1 − χ) averaged over the 2^D children) while every cell
// count stays even and ≥ 4 and the level has more than max_coarse_nodes nodes. The coarsest
// level is solved exactly by a dense Cholesky factorisation.
// Transfers: prolongation P is Q1 interpolation (coarse node P ↦ fine node 2P, weights 1/2
// per axis for fine nodes between coarse ones), restriction R = Pᵀ.
// Smoother: Chebyshev iteration of degree ν on diag(A)⁻¹A over [λmax/range, λmax], the same
// polynomial before and after the coarse correction, so one V-cycle is a symmetric positive
// definite linear map (a valid CG preconditioner). λmax comes from a power iteration, raised
// by a safety factor and capped by the Gershgorin bound.
//
// Vectors are #nodes×m matrices as in shape_feature_operator.hpp; the m columns are
// independent right-hand sides smoothed together (one operator sweep serves all of them).

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "fem/shape_feature_operator.hpp"

namespace bemshape::fem {

struct MultigridOptions {
  /// ν: Chebyshev degree of pre- and post-smoothing (ν operator applications each).
  int smoothing_degree = 3;
  /// λmax/λmin of the interval the Chebyshev polynomial damps: the upper part of the
  /// spectrum that the coarse grid cannot represent (coarsening by 2 per axis).
  double smoothing_range = 12.0;
  /// Coarsening stops once a level has at most this many nodes; that level is factorised
  /// densely (≤ ~1 s and ≤ 20 MB for 1500 unknowns).
  GridIndex max_coarse_nodes = 1500;
};

template <int D>
class Multigrid {
 public:
  Multigrid(ShapeFeatureOperator<D> fine, const MultigridOptions& options = {});

  int num_levels() const { return static_cast<int>(levels_.size()); }
  const ShapeFeatureOperator<D>& fine_operator() const { return levels_.front().op; }
  const ShapeFeatureOperator<D>& level_operator(int level) const { return levels_[level].op; }

  /// z = V-cycle applied to r (zero initial guess), column by column; z ≈ A⁻¹r.
  /// Uses internal scratch space: not safe to call concurrently on one object.
  void apply(const Eigen::MatrixXd& r, Eigen::MatrixXd& z) const;

 private:
  struct Level {
    ShapeFeatureOperator<D> op;
    Eigen::VectorXd inverse_diagonal;  // 0 on boundary nodes: they are never updated
    double lambda_max = 0.0;
    // scratch, sized on first use
    mutable Eigen::MatrixXd b, x, r, d, t;
  };
  void cycle(int level) const;
  void smooth(const Level& level, bool zero_initial_guess, bool want_residual) const;
  void solve_coarsest(const Level& level) const;

  MultigridOptions options_;
  std::vector<Level> levels_;
  std::vector<GridIndex> coarse_unknowns_;  // interior node numbers of the coarsest level
  Eigen::LLT<Eigen::MatrixXd> coarse_factor_;
};

/// Prolongation x_fine += P·x_coarse (Q1 interpolation) between a grid and its halving.
template <int D>
void prolongate_add(const std::array<GridIndex, D>& fine_cells, const Eigen::MatrixXd& coarse,
                    Eigen::MatrixXd& fine);

/// Restriction coarse = Pᵀ·fine (full weighting, the transpose of prolongate_add), zero on
/// coarse boundary nodes.
template <int D>
void restrict_transpose(const std::array<GridIndex, D>& fine_cells, const Eigen::MatrixXd& fine,
                        Eigen::MatrixXd& coarse);

extern template class Multigrid<2>;
extern template class Multigrid<3>;

}  // namespace bemshape::fem
