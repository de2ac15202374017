#include "analysis/measure_features.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "core/errors.hpp"
#include "core/number_text.hpp"

namespace bemshape::analysis {
namespace {

/// Refuses a grid of more than kMaxPoints nodes, naming a spacing that gives fewer.
void refuse_large_grid(const PointGrid& grid, double spacing) {
  const double count = grid.node_count();
  if (count <= kMaxPoints)
    return;
  // Points scale like 1/spacing³; 5 % margin for the rounding up of the cell counts.
  const double coarser = 1.05 * spacing * std::cbrt(count / kMaxPoints);
  throw ResourceError("--grid " + number_text(spacing, 4) + " gives " + number_text(count, 4) +
                      " points (" + std::to_string(grid.cells[0] + 1) + " x " +
                      std::to_string(grid.cells[1] + 1) + " x " +
                      std::to_string(grid.cells[2] + 1) + "), more than the limit of " +
                      number_text(kMaxPoints, 4) + "; use --grid " + number_text(coarser, 4) +
                      " or coarser, or --points with the points of interest");
}

void validate_spacing(double spacing) {
  if (!(std::isfinite(spacing) && spacing > 0.0))
    throw InputError("--grid must be a positive spacing, got " + number_text(spacing, 4));
}

/// Solves, evaluates at result.points and computes the features; `skeleton_width` is the
/// default band half-width.
FeaturesResult measure(FeaturesResult result, const FeaturesOptions& options,
                       std::optional<double> grid_spacing, const ProgressCallback& progress) {
  if (grid_spacing) {
    result.grid = grid_over(result.input.report.bounding_box, *grid_spacing);
    refuse_large_grid(*result.grid, *grid_spacing);
  }
  result.boundary = solve_boundary(result.input, options.solve, result.times, progress);
  if (result.grid)
    result.points = result.grid->nodes();
  report_progress(progress, "evaluate", 0.0);
  result.field = result.times.time("evaluate", [&] {
    // The treecode's error tracks the solver's: no larger than the residual asked for.
    bem::PotentialEvaluationOptions evaluation;
    evaluation.treecode =
        bem::LaplaceTreecodeParameters::for_tolerance(solver_tolerance(options.solve));
    return bem::evaluate_potential(result.boundary.solver_mesh, result.boundary.solution,
                                   result.points, progress, evaluation);
  });
  result.parameters.h0 = options.solve.h0;
  result.parameters.a = options.solve.a;
  result.parameters.skeleton_width =
      options.skeleton_width.value_or(grid_spacing ? *grid_spacing : result.boundary.max_edge);
  report_progress(progress, "features", 0.0);
  result.features = result.times.time("features", [&] {
    return features::compute_features<3>(result.field.s, result.field.gradient, result.field.inside,
                                         result.parameters);
  });
  // h_f and h_p are clamped to 0 where the inverse thickness exceeds 1/a
  // (features/thickness.hpp): a wall thinner than zero, which only the discretisation
  // produces. Counted so that a 0 is not taken for a measured wall.
  for (Eigen::Index p = 0; p < result.points.rows(); ++p)
    if (result.field.inside[static_cast<std::size_t>(p)] &&
        (result.features.h_f(p) == 0.0 || result.features.h_p(p) == 0.0))
      ++result.clamped_points;
  return result;
}

geometry::PreparedMesh read(const std::filesystem::path& file, StageTimes& times,
                            const ProgressCallback& progress) {
  return times.time("read", [&] { return geometry::prepare_mesh_file(file, {}, progress); });
}

}  // namespace

PointGrid grid_over(const geometry::BoundingBox& box, double spacing) {
  PointGrid grid;
  const Eigen::Vector3d centre = 0.5 * (box.min + box.max), extent = box.extent();
  for (int d = 0; d < 3; ++d) {
    grid.cells[d] = static_cast<long long>(std::ceil(extent(d) / spacing)) + 1;
    grid.spacing[d] = spacing;
    grid.origin[d] = centre(d) - 0.5 * spacing * double(grid.cells[d]);
  }
  return grid;
}

Eigen::MatrixX3d PointGrid::nodes() const {
  const long long nx = cells[0] + 1, ny = cells[1] + 1, nz = cells[2] + 1;
  Eigen::MatrixX3d points(nx * ny * nz, 3);
  Eigen::Index row = 0;
  for (long long k = 0; k < nz; ++k)
    for (long long j = 0; j < ny; ++j)
      for (long long i = 0; i < nx; ++i, ++row)
        points.row(row) << origin[0] + double(i) * spacing[0], origin[1] + double(j) * spacing[1],
            origin[2] + double(k) * spacing[2];
  return points;
}

void validate(const FeaturesOptions& options) {
  if (options.skeleton_width && !(*options.skeleton_width >= 0.0))
    throw InputError("--skeleton-width must be a non-negative length");
  validate(options.solve);
}

FeaturesResult measure_features(const geometry::PreparedMesh& input,
                                const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                const FeaturesOptions& options, const ProgressCallback& progress) {
  validate(options);
  FeaturesResult result;
  result.input = input;
  result.points = points;
  return measure(std::move(result), options, std::nullopt, progress);
}

FeaturesResult measure_features_on_grid(const geometry::PreparedMesh& input, double spacing,
                                        const FeaturesOptions& options,
                                        const ProgressCallback& progress) {
  validate_spacing(spacing);
  validate(options);
  FeaturesResult result;
  result.input = input;
  return measure(std::move(result), options, spacing, progress);
}

FeaturesResult measure_features(const std::filesystem::path& file,
                                const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                const FeaturesOptions& options, const ProgressCallback& progress) {
  validate(options);
  FeaturesResult result;
  result.points = points;
  result.input = read(file, result.times, progress);
  return measure(std::move(result), options, std::nullopt, progress);
}

FeaturesResult measure_features_on_grid(const std::filesystem::path& file, double spacing,
                                        const FeaturesOptions& options,
                                        const ProgressCallback& progress) {
  validate_spacing(spacing);
  validate(options);
  FeaturesResult result;
  result.input = read(file, result.times, progress);
  return measure(std::move(result), options, spacing, progress);
}

}  // namespace bemshape::analysis
