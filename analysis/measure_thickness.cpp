#include "analysis/measure_thickness.hpp"

#include <cmath>
#include <utility>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "core/memory_watch.hpp"
#include "core/number_text.hpp"
#include "features/feature_parameters.hpp"
#include "features/thickness.hpp"

namespace bemshape::analysis {
namespace {

ThicknessResult measure(ThicknessResult result, const ThicknessOptions& options,
                        const ProgressCallback& progress) {
  // The memory watch covers the features and the mapping back too (core/memory_watch.hpp).
  const MemoryWatch watch(options.solve.max_memory_bytes);
  const double h0 = options.solve.h0;
  result.boundary = solve_boundary(result.input, options.solve, result.times, progress);
  const geometry::SurfaceMesh& solver_mesh = result.boundary.solver_mesh;
  features::FeatureParameters parameters;
  parameters.h0 = h0;
  parameters.a = options.solve.a;
  parameters.skeleton_width = result.boundary.max_edge;
  const bool paper = options.measure == ThicknessMeasure::paper;
  result.column = paper ? kColumnHf : kColumnHp;
  result.measure_column = paper ? "h_f" : "h_p";
  result.solver_features = result.times.time("features", [&] {
    report_progress(progress, "surface features", 0.0);
    return surface_features(solver_mesh, result.boundary.solution, parameters);
  });
  throw_if_cancelled();  // the features' own loops have no poll points
  result.thickness = result.solver_features.face.col(result.column);
  result.statistics =
      thickness_statistics(solver_mesh, result.thickness, features::kMaxThicknessFactor * h0);
  if (options.min_thickness)
    result.regions = thin_regions(solver_mesh, result.thickness, *options.min_thickness);
  result.clamped_faces = (result.thickness.array() == 0.0).count();
  if (options.map_to_input)
    result.input_features = result.times.time("map_back", [&] {
      report_progress(progress, "map to input mesh", 0.0);
      return transfer_features(solver_mesh, result.solver_features, result.input.mesh);
    });
  throw_if_cancelled();
  return result;
}

}  // namespace

void validate(const ThicknessOptions& options) {
  if (options.min_thickness &&
      !(std::isfinite(*options.min_thickness) && *options.min_thickness > 0.0))
    throw InputError("--min-thickness must be a positive length, got " +
                     number_text(*options.min_thickness, 6));
  validate(options.solve);
}

ThicknessResult measure_thickness(const geometry::PreparedMesh& input,
                                  const ThicknessOptions& options,
                                  const ProgressCallback& progress) {
  validate(options);
  ThicknessResult result;
  result.input = input;
  return measure(std::move(result), options, progress);
}

ThicknessResult measure_thickness(const std::filesystem::path& file,
                                  const ThicknessOptions& options,
                                  const ProgressCallback& progress) {
  validate(options);
  ThicknessResult result;
  result.input =
      result.times.time("read", [&] { return geometry::prepare_mesh_file(file, {}, progress); });
  return measure(std::move(result), options, progress);
}

}  // namespace bemshape::analysis
