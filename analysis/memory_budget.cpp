#include "analysis/memory_budget.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/voxel_resolution.hpp"
#include "bem/solve/dense_transmission_solver.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"
#include "core/number_text.hpp"
#include "fem/voxel_grid.hpp"

namespace bemshape::analysis {
namespace {

/// Step by which the suggested --cell grows while looking for one whose grid fits, and the
/// most steps taken (a factor of 1.1^100 ≈ 10^4 beyond the cell^-D guess).
constexpr double kCellSuggestionStep = 1.1;
constexpr int kCellSuggestionSteps = 100;

/// x rounded up to the 3 significant digits the messages print.
double round_up_3_digits(double x) {
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
  return std::ceil(x / unit) * unit;
}

}  // namespace

std::uint64_t remaining_memory_limit(std::uint64_t max_memory_bytes, std::uint64_t held_bytes) {
  if (max_memory_bytes == 0)
    return 0;
  return max_memory_bytes > held_bytes ? max_memory_bytes - held_bytes : 1;
}

void require_dense_system_fits(const DenseSystemRefusal& refusal) {
  const std::uint64_t budget = memory_budget_bytes(refusal.max_memory_bytes);
  if (budget > 0 && bem::dense_solver_memory_bytes(refusal.solver_faces) > budget)
    refuse_dense_system(refusal, budget);
}

void refuse_dense_system(const DenseSystemRefusal& refusal, std::uint64_t budget) {
  const auto faces = static_cast<double>(refusal.solver_faces);
  const double needed = double(bem::dense_solver_memory_bytes(refusal.solver_faces));
  // 10 % below the limit: the remesher's face count for a given edge varies by a few percent.
  const double fitting_faces = 0.9 * faces * std::sqrt(double(budget) / needed);
  const double edge = refusal.max_edge * std::sqrt(faces / std::max(fitting_faces, 1.0));
  std::ostringstream msg;
  msg << refusal.source << ": the dense BEM solver needs " << number_text(needed / 1e9, 3)
      << " GB for " << refusal.solver_faces << " solver faces (edge "
      << number_text(refusal.max_edge, 3) << ", " << refusal.max_edge_rule << ") but only "
      << number_text(double(budget) / 1e9, 3) << " GB may be used"
      << memory_budget_reason(refusal.max_memory_bytes) << "; use a coarser mesh, e.g. "
      << "--max-edge " << number_text(edge, 3) << " (about " << std::lround(fitting_faces)
      << " faces; flat walls stay accurate up to --max-edge "
      << number_text(refusal.flat_wall_max_edge, 3) << ")";
  throw ResourceError(msg.str());
}

template <int D>
fem::GridCheck<D> voxel_grid_memory_check(const VoxelMemoryBudget& budget,
                                          const features::FeatureParameters& parameters) {
  return [budget, p = parameters](const fem::PlannedGrid<D>& planned) {
    const auto bytes = fem::estimated_run_bytes<D>;
    const double needed = bytes(planned.grid.num_cells());
    const auto allowed = static_cast<double>(memory_budget_bytes(budget.max_memory_bytes));
    if (allowed == 0.0 || needed <= allowed)
      return;
    // The smallest cell that fits, h0 following it or fixed; 0 if none within the steps.
    // The cell count falls like cell^-D at most: the search starts there.
    const auto fitting_cell = [&](bool h0_follows_cell) {
      double cell = round_up_3_digits(budget.cell * std::pow(needed / allowed, 1.0 / D));
      for (int step = 0; step < kCellSuggestionSteps; ++step) {
        features::FeatureParameters q = p;
        if (h0_follows_cell)
          q.h0 = kDefaultH0Cells * cell;
        if (bytes(planned.cells_with(cell, q)) <= allowed)
          return cell;
        cell = round_up_3_digits(cell * kCellSuggestionStep);
      }
      return 0.0;
    };
    std::ostringstream what, instead;
    what.precision(3);
    instead.precision(3);
    what << budget.input << ": the voxel FEM on " << planned.grid.num_cells() << " cells (";
    for (int d = 0; d < D; ++d)
      what << (d ? " x " : "") << planned.grid.cells[d];
    what << " of size " << budget.cell << ", --cell)";
    double cell = fitting_cell(!budget.h0_given);
    if (cell > 0.0) {
      instead << "use a larger cell size, e.g. --cell " << cell;
    } else if (!budget.h0_given && (cell = fitting_cell(false)) > 0.0) {
      instead << "no cell size fits with the default h0 of " << kDefaultH0Cells
              << " cells (the margin around the part grows with it); keep this run's h0 with a "
                 "larger cell size, e.g. --cell "
              << cell << " --h0 " << p.h0 << ", or raise --max-memory";
    } else {
      instead << "raise --max-memory or use a machine with more memory";
    }
    require_memory(static_cast<std::uint64_t>(needed), what.str(), instead.str(),
                   budget.max_memory_bytes);
  };
}

template <int D>
fem::PixelCheck image_memory_check(const VoxelMemoryBudget& budget) {
  return [budget](fem::GridIndex pixels) {
    const double needed = kImageReadBytesPerPixel<D> * static_cast<double>(pixels);
    std::ostringstream what;
    what << budget.input << ": reading its " << pixels << (D == 2 ? " pixels" : " voxels");
    require_memory(static_cast<std::uint64_t>(needed), what.str(),
                   "downsample the image or raise --max-memory", budget.max_memory_bytes);
  };
}

template fem::GridCheck<2> voxel_grid_memory_check<2>(const VoxelMemoryBudget&,
                                                      const features::FeatureParameters&);
template fem::GridCheck<3> voxel_grid_memory_check<3>(const VoxelMemoryBudget&,
                                                      const features::FeatureParameters&);
template fem::PixelCheck image_memory_check<2>(const VoxelMemoryBudget&);
template fem::PixelCheck image_memory_check<3>(const VoxelMemoryBudget&);

}  // namespace bemshape::analysis
