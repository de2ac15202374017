#include "analysis/memory_budget.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/voxel_resolution.hpp"
#include "bem/solve/dense_transmission_solver.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"
#include "core/number_text.hpp"
#include "core/solver_memory_refusal.hpp"
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
  throw SolverMemoryRefusal(msg.str(), SolverMemoryRefusal::Solver::dense,
                            long(refusal.solver_faces), needed, double(budget), 0.0);
}

double fitting_solver_faces(const SolverMemoryRefusal& refused, long dense_up_to) {
  const double room = kFitMargin * refused.budget_bytes;
  const auto held = std::uint64_t(std::max(refused.held_bytes, 0.0));
  // Above dense_up_to faces the hierarchical-matrix path solves. Its estimate depends on the
  // geometry (near field, ranks) but beyond what the process holds grows about like N: the
  // refused mesh's own estimate scaled to the room left.
  if (refused.solver == SolverMemoryRefusal::Solver::hmatrix) {
    const double per_face_need =
        std::max(refused.needed_bytes - refused.held_bytes, 1.0) / double(refused.faces);
    const double faces = std::max(room - refused.held_bytes, 0.0) / per_face_need;
    if (faces > double(dense_up_to))
      return faces;
  }
  // At or below dense_up_to the dense path solves, and its bound (what the process holds,
  // the system and its copy, the work per face) is a closed form increasing in N: the
  // largest N whose bound fits, by bisection.
  long low = 0, high = std::min(refused.faces, dense_up_to) + 1;
  while (high - low > 1) {
    const long mid = low + (high - low) / 2;
    (double(bem::dense_solver_peak_bytes(mid, held)) <= room ? low : high) = mid;
  }
  return double(low);
}

double fitting_edge_text_value(double edge) {
  return std::stod(number_text(round_up_3_digits(edge), 3));
}

double uniform_mesh_edge_for_faces(double area, double faces) {
  return std::sqrt(area / (kRemeshedFaceAreaRatio * std::max(faces, 1.0)));
}

std::string fitting_mesh_accuracy(double edge, double h0, double a) {
  const double surface_values_edge = 1.5 * a * h0, flat_wall_edge = 2.5 * a * h0;
  if (edge <= surface_values_edge)
    return "as accurate as the default: values on the surface within about 1 %";
  if (edge <= flat_wall_edge)
    return "flat walls stay accurate up to --max-edge " + number_text(flat_wall_edge, 3) +
           ", curved walls lose some accuracy beyond 1.5*a*h0 = " +
           number_text(surface_values_edge, 3);
  return "coarser than 2.5*a*h0 = " + number_text(flat_wall_edge, 3) +
         ", the largest edge at which flat walls stay accurate: the readings are not "
         "validated there; a larger --max-memory keeps them accurate";
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
