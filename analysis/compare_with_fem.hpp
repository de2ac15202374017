#pragma once
// One closed surface solved twice, by the boundary element method (the solver mesh and the
// representation formula at interior points: analysis/boundary_solve.hpp,
// bem/evaluate/potential_evaluation.hpp) and by the voxel finite-element method (the input
// mesh voxelised with cells of side `cell`: fem/), and f_h and h_p compared at interior
// probe points. The whole of `bemshape compare` but reading options and printing.
//
// Probes: centres of the FEM's solid cells (χ ≥ ½) whose distance to the input surface is at
// least kProbeDepthCells·cell, where both solutions are smooth and the FEM's staircase
// boundary does not dominate; at most `max_probes` of them, spread evenly over that set.
// At each probe the relative difference is |FEM − BEM| / |BEM| (the BEM is the reference:
// its errors on the closed forms are ten times smaller, docs/validation.md).

#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "analysis/boundary_solve.hpp"
#include "analysis/histogram.hpp"
#include "analysis/stage_times.hpp"
#include "core/progress.hpp"
#include "features/feature_parameters.hpp"
#include "fem/shape_feature_solver.hpp"
#include "fem/voxel_grid.hpp"
#include "geometry/mesh_preparation.hpp"

namespace bemshape::analysis {

/// Probes lie at least this many cells from the surface. Within a cell or two of it the FEM
/// sees the staircase of its voxels instead of the surface and its ∇s is a difference
/// quotient across the jump of χ; two cells is where both methods describe the same solid.
inline constexpr double kProbeDepthCells = 2.0;
/// Default cap on the probes. The BEM evaluates each probe against every solver face (two
/// kernels, Laplace and Yukawa): 2000 probes on the 1280-face ball take 8–20 s on two busy
/// cores, about as long as its dense solve, and the median and 95th percentile of 2000
/// samples are stable to a few per cent of their value. Probes within a panel diameter of
/// the surface cost several times more (near-surface interpolation, polar quadrature): on
/// thin walls meshed coarsely, use fewer (docs/usage.md).
inline constexpr long long kDefaultMaxProbes = 2000;
/// Bins of the h_p differences' histogram.
inline constexpr int kHistogramBins = 12;

struct CompareOptions {
  /// h0, a, solver mesh, solver, memory, for both methods. The FEM grid's memory comes off
  /// max_memory_bytes for the BEM solve: its χ stays allocated through it.
  SolveOptions solve;
  /// h0 = kDefaultH0Cells·cell (analysis/voxel_resolution.hpp) instead of solve.h0: the
  /// command's default when --h0 is not given. A grid refused for memory is then answered
  /// with cells whose h0 follows them.
  bool h0_follows_cell = false;
  double cell = 0.0;                         ///< FEM grid cell size [model units], > 0
  long long max_probes = kDefaultMaxProbes;  ///< ≥ 1
};

/// The feature parameters of the comparison: h0 (solve.h0 or from the cell), a, and the
/// cell as the skeleton width. Throws InputError for a cell, max_probes, h0 or a out of
/// range (compare_with_fem checks these and then validate(solve) before any work).
features::FeatureParameters comparison_parameters(const CompareOptions& options);

/// The voxel side of the comparison.
struct VoxelProbes {
  fem::VoxelGrid<3> grid;
  long long solid_cells = 0;
  long long deep_cells = 0;  ///< solid cells at least kProbeDepthCells from the surface
  std::vector<fem::GridIndex> probe_cells;
  Eigen::MatrixX3d probes;  ///< #probes×3 cell centres [model units]
};

/// Relative differences of one feature at the probes, and their statistics (fractions).
struct Difference {
  Eigen::VectorXd relative;  ///< |FEM − BEM| / |BEM| at the probes used
  double median = 0.0, p95 = 0.0, max = 0.0;
  double median_signed = 0.0;  ///< median of (FEM − BEM) / |BEM|: the FEM's bias
  Eigen::Vector3d max_location = Eigen::Vector3d::Zero();
  long long left_out = 0;  ///< probes not measurable by either method (saturated)
};

struct FemComparison {
  geometry::PreparedMesh input;            ///< the validated, repaired input and its report
  features::FeatureParameters parameters;  ///< h0, a, skeleton width (the cell)
  VoxelProbes voxels;
  BoundarySolve boundary;  ///< solver mesh, max edge and its rule, φ and q
  fem::FemSolveReport fem_report;
  long long outside_bem = 0;  ///< probes the BEM's winding number puts outside (left out)
  Difference f_h, h_p;
  Histogram h_p_histogram;  ///< of h_p.relative, kHistogramBins at most
  /// Wall time of the stages: "read" (file input only), "voxelise", "probes", "refine",
  /// "assemble", "solve", "fem_solve", "fem_features", "evaluate", "features".
  StageTimes times;
};

/// Compares the two methods on the solid bounded by `input`. Throws InputError when no cell
/// centre is deep enough for a probe (naming a --cell that gives some) or h_p is measurable
/// at no probe, ResourceError when the grid or the BEM system does not fit in memory.
FemComparison compare_with_fem(const geometry::PreparedMesh& input, const CompareOptions& options,
                               const ProgressCallback& progress = {});

/// The same for a mesh file, read, validated and repaired first (stage "read").
FemComparison compare_with_fem(const std::filesystem::path& file, const CompareOptions& options,
                               const ProgressCallback& progress = {});

}  // namespace bemshape::analysis
