#include "fem/voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.hpp"

namespace bemshape::fem {

double required_margin(const features::FeatureParameters& parameters) {
  return std::max(parameters.h0, 12.0 / parameters.kappa());
}

template <int D>
std::array<GridIndex, D> multigrid_friendly_cells(const std::array<GridIndex, D>& needed,
                                                  GridIndex max_coarse_nodes) {
  // Smallest common power of two whose coarsest grid is small enough for a dense solve.
  for (int k = 0;; ++k) {
    const GridIndex factor = GridIndex{1} << k;
    std::array<GridIndex, D> coarse{};
    GridIndex nodes = 1;
    for (int d = 0; d < D; ++d) {
      coarse[d] = std::max<GridIndex>(2, (needed[d] + factor - 1) / factor);
      nodes *= coarse[d] + 1;
    }
    if (nodes <= max_coarse_nodes || k >= 40) {
      std::array<GridIndex, D> cells{};
      for (int d = 0; d < D; ++d)
        cells[d] = coarse[d] * factor;
      return cells;
    }
  }
}

template <int D>
VoxelGrid<D> grid_around(const Eigen::Matrix<double, D, 1>& lo,
                         const Eigen::Matrix<double, D, 1>& hi, double cell_size,
                         const features::FeatureParameters& parameters, GridIndex max_cells,
                         bool align_to_lo) {
  features::validate(parameters);
  if (!(cell_size > 0.0) || !std::isfinite(cell_size))
    throw InputError("voxel grid: the cell size must be a positive number (got " +
                     std::to_string(cell_size) + ")");
  if (!lo.allFinite() || !hi.allFinite() || (hi - lo).minCoeff() < 0.0)
    throw InputError("voxel grid: the solid's bounding box is empty or not finite");
  const double margin = required_margin(parameters);
  std::array<GridIndex, D> needed{};
  double total = 1.0;
  for (int d = 0; d < D; ++d) {
    // One extra cell when aligning: the shift onto the lattice through lo eats up to one.
    const double cells =
        std::ceil((hi(d) - lo(d) + 2.0 * margin) / cell_size) + (align_to_lo ? 1.0 : 0.0);
    total *= cells;
    needed[d] = static_cast<GridIndex>(std::min(cells, 1e15));
  }
  if (total > static_cast<double>(max_cells))
    throw ResourceError("voxel grid: cell size " + std::to_string(cell_size) + " needs about " +
                        std::to_string(static_cast<double>(total)) + " cells (limit " +
                        std::to_string(max_cells) + "); use a larger cell size");
  // The dense coarse solve of multigrid.hpp stays cheap up to this many nodes.
  constexpr GridIndex kCoarseNodes = D == 2 ? 1200 : 1500;
  VoxelGrid<D> grid;
  grid.cells = multigrid_friendly_cells<D>(needed, kCoarseNodes);
  grid.cell_size = cell_size;
  for (int d = 0; d < D; ++d) {
    const double width = static_cast<double>(grid.cells[d]) * cell_size;
    grid.origin(d) = 0.5 * (lo(d) + hi(d)) - 0.5 * width;
    if (align_to_lo)
      grid.origin(d) = lo(d) - std::ceil((lo(d) - grid.origin(d)) / cell_size) * cell_size;
  }
  if (grid.num_cells() > max_cells)
    throw ResourceError("voxel grid: " + std::to_string(grid.num_cells()) +
                        " cells exceed the limit of " + std::to_string(max_cells) +
                        "; use a larger cell size");
  return grid;
}

template std::array<GridIndex, 2> multigrid_friendly_cells<2>(const std::array<GridIndex, 2>&,
                                                              GridIndex);
template std::array<GridIndex, 3> multigrid_friendly_cells<3>(const std::array<GridIndex, 3>&,
                                                              GridIndex);
template VoxelGrid<2> grid_around<2>(const Eigen::Vector2d&, const Eigen::Vector2d&, double,
                                     const features::FeatureParameters&, GridIndex, bool);
template VoxelGrid<3> grid_around<3>(const Eigen::Vector3d&, const Eigen::Vector3d&, double,
                                     const features::FeatureParameters&, GridIndex, bool);

}  // namespace bemshape::fem
