#pragma once
// Solves the shape-feature PDE on a voxel grid (paper, section "Formulation"):
//
//   −div(ã ∇s_i − e_i χ) + α(1 − χ) s_i = 0 in Ω_R,  s_i = 0 on ∂Ω_R,  i = 1..D,
//   ã = a·h0², α = 4/a,
//
// with Q1 elements (shape_feature_operator.hpp), all D components at once by conjugate
// gradients (linalg/conjugate_gradient.hpp) preconditioned with one geometric multigrid V-cycle
// (multigrid.hpp). Iteration counts do not grow with the grid.

#include <vector>

#include <Eigen/Core>

#include "core/progress.hpp"
#include "features/feature_parameters.hpp"
#include "fem/multigrid.hpp"
#include "fem/voxel_grid.hpp"

namespace bemshape::fem {

/// Default CG stopping criterion ‖b − As‖ ≤ tol·‖b‖ per component. The features are
/// derivatives of s resolved to a discretisation error ≳ 1e−4 on any grid that fits in
/// memory, and the algebraic error is about κ(A_MG⁻¹A)·tol, far below that at 1e−8.
inline constexpr double kDefaultRelativeTolerance = 1e-8;

struct FemSolveOptions {
  double relative_tolerance = kDefaultRelativeTolerance;
  /// A multigrid-preconditioned CG that needs more than this has a broken input (NaN, a
  /// degenerate grid); typical counts are 8–15.
  int max_iterations = 200;
  MultigridOptions multigrid;
};

struct FemSolveReport {
  int iterations = 0;                      ///< CG iterations (all components together)
  int multigrid_levels = 0;                ///< levels of the V-cycle, fine to coarsest
  std::vector<double> relative_residuals;  ///< final ‖b_i − As_i‖/‖b_i‖ per component
  double setup_seconds = 0.0;              ///< operator, load and hierarchy construction
  double solve_seconds = 0.0;              ///< conjugate gradients
};

template <int D>
struct FemSolution {
  Eigen::MatrixXd s;  ///< #nodes×D nodal values of s_1..s_D [model units], 0 on ∂Ω_R
  FemSolveReport report;
};

/// Solves for s on `grid` (χ must be filled). Throws InputError for invalid parameters,
/// NumericalError if CG does not converge. Progress stages: "multigrid setup",
/// "conjugate gradients".
template <int D>
FemSolution<D> solve_shape_feature_pde(const VoxelGrid<D>& grid,
                                       const features::FeatureParameters& parameters,
                                       const FemSolveOptions& options = {},
                                       const ProgressCallback& progress = {});

extern template FemSolution<2> solve_shape_feature_pde<2>(const VoxelGrid<2>&,
                                                          const features::FeatureParameters&,
                                                          const FemSolveOptions&,
                                                          const ProgressCallback&);
extern template FemSolution<3> solve_shape_feature_pde<3>(const VoxelGrid<3>&,
                                                          const features::FeatureParameters&,
                                                          const FemSolveOptions&,
                                                          const ProgressCallback&);

}  // namespace bemshape::fem
