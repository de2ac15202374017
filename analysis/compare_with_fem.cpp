#include "analysis/compare_with_fem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "analysis/memory_budget.hpp"
#include "analysis/thickness_statistics.hpp"
#include "analysis/voxel_resolution.hpp"
#include "bem/evaluate/potential_evaluation.hpp"
#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "features/point_features.hpp"
#include "features/thickness.hpp"
#include "fem/characteristic_function.hpp"
#include "fem/voxel_features.hpp"
#include "geometry/closest_point.hpp"

namespace bemshape::analysis {
namespace {

/// Evenly spread subset of m out of n items: indices ⌊(i + ½)·n/m⌋, i = 0 … m − 1.
std::vector<fem::GridIndex> spread_subset(const std::vector<fem::GridIndex>& items, long long m) {
  const auto n = static_cast<long long>(items.size());
  if (n <= m)
    return items;
  std::vector<fem::GridIndex> subset;
  subset.reserve(static_cast<std::size_t>(m));
  for (long long i = 0; i < m; ++i)
    subset.push_back(items[static_cast<std::size_t>((2 * i + 1) * n / (2 * m))]);
  return subset;
}

/// Voxelises the input mesh as `bemshape fem` does and picks the probe cells. Throws
/// InputError when no solid cell centre is deep enough, with a --cell that gives some.
VoxelProbes voxelise_and_pick_probes(const CompareOptions& options,
                                     const geometry::PreparedMesh& input,
                                     const features::FeatureParameters& parameters,
                                     StageTimes& times) {
  VoxelProbes side;
  const geometry::SurfaceMesh& mesh = input.mesh;
  const VoxelMemoryBudget budget{input.report.source, options.cell, !options.h0_follows_cell,
                                 options.solve.max_memory_bytes};
  side.grid = times.time("voxelise", [&] {
    return fem::grid_for_mesh(mesh, options.cell, parameters, 1, fem::kDefaultMaxCells<3>,
                              voxel_grid_memory_check<3>(budget, parameters));
  });
  std::vector<fem::GridIndex> solid;
  for (fem::GridIndex e = 0; e < side.grid.num_cells(); ++e)
    if (side.grid.chi[static_cast<std::size_t>(e)] >= fem::kSolidFraction)
      solid.push_back(e);
  side.solid_cells = static_cast<long long>(solid.size());
  const double depth = kProbeDepthCells * options.cell;
  std::vector<fem::GridIndex> deep;
  double deepest = 0.0;
  times.time("probes", [&] {
    Eigen::MatrixX3d centres(static_cast<Eigen::Index>(solid.size()), 3);
    for (std::size_t k = 0; k < solid.size(); ++k)
      centres.row(static_cast<Eigen::Index>(k)) =
          side.grid.cell_centre(side.grid.cell_multi_index(solid[k])).transpose();
    const geometry::ClosestPointQuery surface(mesh);
    const Eigen::VectorXd distance = surface.closest_points(centres).distances;
    for (std::size_t k = 0; k < solid.size(); ++k) {
      const double d = distance(static_cast<Eigen::Index>(k));
      deepest = std::max(deepest, d);
      if (d >= depth)
        deep.push_back(solid[k]);
    }
  });
  if (deep.empty())
    // The deepest centre at cell c is within c·√3/2 of the deepest point of the solid, so
    // a third of its depth leaves room for two cells and the offset of the centres.
    throw InputError(input.report.source + ": no probe point: none of the " +
                     std::to_string(side.solid_cells) + " solid cell centres of --cell " +
                     number_text(options.cell, 4) + " lies at least " +
                     number_text(kProbeDepthCells, 2) + " cells (" + number_text(depth, 4) +
                     ") inside the surface (the deepest is " + number_text(deepest, 4) +
                     " inside); use a smaller --cell" +
                     (deepest > 0.0 ? ", e.g. --cell " + number_text(deepest / 3.0, 3) : ""));
  side.deep_cells = static_cast<long long>(deep.size());
  side.probe_cells = spread_subset(deep, options.max_probes);
  side.probes.resize(static_cast<Eigen::Index>(side.probe_cells.size()), 3);
  for (std::size_t k = 0; k < side.probe_cells.size(); ++k)
    side.probes.row(static_cast<Eigen::Index>(k)) =
        side.grid.cell_centre(side.grid.cell_multi_index(side.probe_cells[k])).transpose();
  return side;
}

/// Statistics of |fem − bem| / |bem| over the probes with use[k] set; probes where either
/// value reaches `unmeasurable_from` (the saturation value of h_p far from any wall) are
/// left out and counted.
Difference difference(const Eigen::VectorXd& fem, const Eigen::VectorXd& bem,
                      const std::vector<char>& use, const Eigen::MatrixX3d& probes,
                      double unmeasurable_from) {
  Difference d;
  std::vector<double> relative, signed_relative;
  std::vector<Eigen::Index> where;
  for (Eigen::Index k = 0; k < bem.size(); ++k) {
    if (!use[static_cast<std::size_t>(k)])
      continue;
    if (!(std::abs(bem(k)) > 0.0) || fem(k) >= unmeasurable_from || bem(k) >= unmeasurable_from) {
      ++d.left_out;
      continue;
    }
    signed_relative.push_back((fem(k) - bem(k)) / std::abs(bem(k)));
    relative.push_back(std::abs(signed_relative.back()));
    where.push_back(k);
  }
  d.relative = Eigen::Map<const Eigen::VectorXd>(relative.data(),
                                                 static_cast<Eigen::Index>(relative.size()));
  if (relative.empty())
    return d;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(d.relative.size());
  const Eigen::Map<const Eigen::VectorXd> signed_values(signed_relative.data(), d.relative.size());
  d.median = weighted_quantile(d.relative, ones, 0.5);
  d.p95 = weighted_quantile(d.relative, ones, 0.95);
  d.median_signed = weighted_quantile(signed_values, ones, 0.5);
  Eigen::Index worst = 0;
  d.max = d.relative.maxCoeff(&worst);
  d.max_location = probes.row(where[static_cast<std::size_t>(worst)]).transpose();
  return d;
}

/// The BEM's options: solve with the comparison's h0.
SolveOptions bem_options(const CompareOptions& options) {
  SolveOptions solve = options.solve;
  solve.h0 = comparison_parameters(options).h0;
  return solve;
}

FemComparison compare(FemComparison c, const CompareOptions& options,
                      const ProgressCallback& progress) {
  c.parameters = comparison_parameters(options);
  const features::FeatureParameters& parameters = c.parameters;
  report_progress(progress, "voxelise", 0.0);
  c.voxels = voxelise_and_pick_probes(options, c.input, parameters, c.times);
  // The two solves run one after the other, each within --max-memory, but the grid's χ
  // stays allocated through the BEM solve.
  SolveOptions solve = bem_options(options);
  solve.max_memory_bytes =
      remaining_memory_limit(options.solve.max_memory_bytes,
                             static_cast<std::uint64_t>(c.voxels.grid.chi.size() * sizeof(float)));
  c.boundary = solve_boundary(c.input, solve, c.times, progress);

  report_progress(progress, "fem solve", 0.0);
  const fem::FemSolution<3> fem_solution = c.times.time("fem_solve", [&] {
    return fem::solve_shape_feature_pde<3>(c.voxels.grid, parameters, {}, progress);
  });
  c.fem_report = fem_solution.report;
  report_progress(progress, "fem features", 0.0);
  const fem::VoxelFeatures<3> fem_features = c.times.time("fem_features", [&] {
    return fem::voxel_features<3>(c.voxels.grid, fem_solution.s, parameters);
  });

  report_progress(progress, "evaluate", 0.0);
  const bem::PotentialField field = c.times.time("evaluate", [&] {
    return bem::evaluate_potential(c.boundary.solver_mesh, c.boundary.solution, c.voxels.probes,
                                   progress);
  });
  const features::FeatureField<3> bem_features = c.times.time("features", [&] {
    return features::compute_features<3>(field.s, field.gradient, field.inside, parameters);
  });

  const Eigen::Index np = c.voxels.probes.rows();
  Eigen::VectorXd fem_f_h(np), fem_h_p(np);
  for (Eigen::Index k = 0; k < np; ++k) {
    const auto cell = static_cast<Eigen::Index>(c.voxels.probe_cells[static_cast<std::size_t>(k)]);
    fem_f_h(k) = fem_features.field.f_h(cell);
    fem_h_p(k) = fem_features.field.h_p(cell);
    c.outside_bem += !field.inside[static_cast<std::size_t>(k)];
  }
  // f_h has no saturation value; h_p saturates at kMaxThicknessFactor·h0 (thickness.hpp).
  c.f_h = difference(fem_f_h, bem_features.f_h, field.inside, c.voxels.probes,
                     std::numeric_limits<double>::infinity());
  c.h_p = difference(fem_h_p, bem_features.h_p, field.inside, c.voxels.probes,
                     features::kMaxThicknessFactor * parameters.h0);
  if (c.h_p.relative.size() == 0)
    throw InputError(c.input.report.source + ": h_p is not measurable at any of the " +
                     std::to_string(np) + " probes (no opposite wall within reach of h0 = " +
                     number_text(parameters.h0, 4) + "); use a larger --h0");
  c.h_p_histogram = histogram(c.h_p.relative, kHistogramBins);
  return c;
}

}  // namespace

features::FeatureParameters comparison_parameters(const CompareOptions& options) {
  if (!(std::isfinite(options.cell) && options.cell > 0.0))
    throw InputError("--cell must be a positive length, got " + number_text(options.cell, 4));
  if (options.max_probes < 1)
    throw InputError("--max-probes must be at least 1, got " + std::to_string(options.max_probes));
  features::FeatureParameters parameters;
  parameters.h0 = options.h0_follows_cell ? kDefaultH0Cells * options.cell : options.solve.h0;
  parameters.a = options.solve.a;
  parameters.skeleton_width = options.cell;
  features::validate(parameters);
  return parameters;
}

FemComparison compare_with_fem(const geometry::PreparedMesh& input, const CompareOptions& options,
                               const ProgressCallback& progress) {
  validate(bem_options(options));  // every option's check, before any work
  FemComparison c;
  c.input = input;
  return compare(std::move(c), options, progress);
}

FemComparison compare_with_fem(const std::filesystem::path& file, const CompareOptions& options,
                               const ProgressCallback& progress) {
  validate(bem_options(options));
  FemComparison c;
  c.input = c.times.time("read", [&] { return geometry::prepare_mesh_file(file, {}, progress); });
  return compare(std::move(c), options, progress);
}

}  // namespace bemshape::analysis
