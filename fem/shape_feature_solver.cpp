#include "fem/shape_feature_solver.hpp"

#include <chrono>
#include <string>

#include "core/errors.hpp"
#include "linalg/conjugate_gradient.hpp"
#include "fem/shape_feature_operator.hpp"

namespace bemshape::fem {

template <int D>
FemSolution<D> solve_shape_feature_pde(const VoxelGrid<D>& grid,
                                       const features::FeatureParameters& parameters,
                                       const FemSolveOptions& options,
                                       const ProgressCallback& progress) {
  features::validate(parameters);
  if (static_cast<GridIndex>(grid.chi.size()) != grid.num_cells())
    throw InputError("voxel solver: the grid's characteristic function has " +
                     std::to_string(grid.chi.size()) + " values for " +
                     std::to_string(grid.num_cells()) + " cells");
  for (int d = 0; d < D; ++d)
    if (grid.cells[d] < 2)
      throw InputError("voxel solver: the grid needs at least two cells along every axis");
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  report_progress(progress, "multigrid setup", 0.0);
  const Eigen::MatrixXd load = shape_feature_load<D>(grid);
  Multigrid<D> multigrid(ShapeFeatureOperator<D>(grid.cells, grid.cell_size, parameters.a_tilde(),
                                                 reaction_coefficient<D>(grid, parameters.alpha())),
                         options.multigrid);
  report_progress(progress, "multigrid setup", 1.0);
  const auto setup_end = Clock::now();

  FemSolution<D> solution;
  solution.s.setZero(grid.num_nodes(), D);
  const auto cg = linalg::conjugate_gradient(multigrid.fine_operator(), multigrid, load, solution.s,
                                     options.relative_tolerance, options.max_iterations, progress);
  const auto end = Clock::now();
  solution.report.iterations = cg.iterations;
  solution.report.multigrid_levels = multigrid.num_levels();
  solution.report.relative_residuals = cg.relative_residuals;
  solution.report.setup_seconds = std::chrono::duration<double>(setup_end - start).count();
  solution.report.solve_seconds = std::chrono::duration<double>(end - setup_end).count();
  return solution;
}

template FemSolution<2> solve_shape_feature_pde<2>(const VoxelGrid<2>&,
                                                   const features::FeatureParameters&,
                                                   const FemSolveOptions&, const ProgressCallback&);
template FemSolution<3> solve_shape_feature_pde<3>(const VoxelGrid<3>&,
                                                   const features::FeatureParameters&,
                                                   const FemSolveOptions&, const ProgressCallback&);

}  // namespace bemshape::fem
