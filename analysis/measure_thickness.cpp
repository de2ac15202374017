#include "analysis/measure_thickness.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "core/memory_watch.hpp"
#include "core/number_text.hpp"
#include "features/feature_parameters.hpp"
#include "features/thickness.hpp"

namespace bemshape::analysis {
namespace {

/// Whether any face of `mesh` is measurable (thickness_statistics' rule).
bool any_measurable(const geometry::SurfaceMesh& mesh, const Eigen::VectorXd& thickness,
                    double unmeasurable_from) {
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    if (measurable_face(mesh, thickness, f, unmeasurable_from))
      return true;
  return false;
}

/// The statistics of a surface on which nothing is measurable: NaN figures, all of its area
/// unmeasurable.
ThicknessStatistics unmeasurable_statistics(const geometry::SurfaceMesh& mesh) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  ThicknessStatistics stats;
  stats.minimum = stats.maximum = stats.mean = stats.median = stats.p05 = stats.p95 = nan;
  stats.min_location = Eigen::Vector3d::Constant(nan);
  stats.unmeasurable_area = mesh.area();
  return stats;
}

/// Drops regions smaller than `min_area`.
template <class Region>
void drop_small(std::vector<Region>& regions, double min_area) {
  std::erase_if(regions, [min_area](const Region& r) { return r.area < min_area; });
}

ThicknessResult measure(ThicknessResult result, const ThicknessOptions& given,
                        const ProgressCallback& progress) {
  ThicknessOptions options = given;
  if (options.h0_from_part) {
    options.solve.h0 = part_h0(result.input.report);
    result.h0_rule = "2*volume/area of the part";
  } else {
    result.h0_rule = "--h0";
  }
  // The memory watch covers the features and the mapping back too (core/memory_watch.hpp).
  const MemoryWatch watch(options.solve.max_memory_bytes);
  const double h0 = options.solve.h0;
  result.h0 = h0;
  if (options.measure == ThicknessMeasure::wall)
    options.solve.mesh_rule = SolverMeshRule::wall_reading;
  result.boundary = solve_boundary(result.input, options.solve, result.times, progress);
  const geometry::SurfaceMesh& solver_mesh = result.boundary.solver_mesh;
  result.defect_faces =
      geometry::faces_near_defects(solver_mesh, result.input.report.defects, h0);
  features::FeatureParameters parameters;
  parameters.h0 = h0;
  parameters.a = options.solve.a;
  parameters.skeleton_width = result.boundary.max_edge;
  switch (options.measure) {
    case ThicknessMeasure::wall:
      result.column = kColumnWall;
      result.measure_column = "wall";
      break;
    case ThicknessMeasure::principal:
      result.column = kColumnHp;
      result.measure_column = "h_p";
      break;
    case ThicknessMeasure::paper:
      result.column = kColumnHf;
      result.measure_column = "h_f";
      break;
  }
  result.solver_features = result.times.time("features", [&] {
    report_progress(progress, "surface features", 0.0);
    return surface_features(solver_mesh, result.boundary.solution, parameters);
  });
  throw_if_cancelled();  // the features' own loops have no poll points
  if (options.measure == ThicknessMeasure::wall) {
    result.wall =
        wall_thickness(solver_mesh, result.boundary.solution, parameters, progress, &result.times);
    Eigen::VectorXd wall = result.wall.thickness;
    if (options.edges == EdgeMode::exact)
      wall = wall.cwiseMin(result.solver_features.face.col(kColumnHp));
    result.solver_features.face.col(kColumnWall) = wall;
    result.solver_features.vertex.col(kColumnWall) = vertex_mean(solver_mesh, wall);
  }
  result.thickness = result.solver_features.face.col(result.column);
  const auto regions_start = StageTimes::Clock::now();
  const double unmeasurable_from = features::kMaxThicknessFactor * h0;
  result.min_region_area = speck_area(options.min_region_area, h0, solver_mesh.area());
  result.histogram = area_histogram(result.thickness, solver_mesh.face_areas(), kHistogramBins,
                                    unmeasurable_from);
  if (options.unmeasurable_fails_check && options.min_thickness &&
      !any_measurable(solver_mesh, result.thickness, unmeasurable_from)) {
    result.statistics = unmeasurable_statistics(solver_mesh);
    result.check.speck_area = result.min_region_area;
    result.check.pass = false;
    result.check.unmeasurable = true;
  } else {
    result.statistics = thickness_statistics(solver_mesh, result.thickness, unmeasurable_from);
    if (options.min_thickness) {
      result.regions = thin_regions(solver_mesh, result.thickness, *options.min_thickness,
                                    result.wall.partner);
      result.check = thin_check(result.regions, result.min_region_area);
    }
    if (options.max_thickness) {
      result.thick_regions =
          thick_regions(solver_mesh, result.thickness, *options.max_thickness,
                        unmeasurable_from, result.wall.partner);
      drop_small(result.thick_regions, result.min_region_area);
      if (result.wall.mid_point.rows() == solver_mesh.num_faces())
        for (ThickRegion& r : result.thick_regions)
          r.skeleton_point = result.wall.mid_point.row(r.extreme_face).transpose();
    }
  }
  result.clamped_faces = (result.thickness.array() == 0.0).count();
  result.times.add("regions", std::chrono::duration<double>(StageTimes::Clock::now() -
                                                             regions_start).count());
  if (options.map_to_input)
    result.input_features = result.times.time("map_back", [&] {
      report_progress(progress, "map to input mesh", 0.0);
      return transfer_features(solver_mesh, result.solver_features, result.input.mesh);
    });
  throw_if_cancelled();
  return result;
}

}  // namespace

ThicknessMeasure thickness_measure(const std::string& name) {
  if (name == "wall")
    return ThicknessMeasure::wall;
  if (name == "principal" || name == "sphere")
    return ThicknessMeasure::principal;
  if (name == "paper")
    return ThicknessMeasure::paper;
  throw InputError("--measure must be 'wall' (the default: the thickness of the wall a point "
                   "belongs to), 'sphere' (alias 'principal': h_p, the inscribed-sphere "
                   "diameter at the point) or 'paper' (h_f), got '" + name + "'");
}

EdgeMode edge_mode(const std::string& name) {
  if (name == "wall")
    return EdgeMode::wall;
  if (name == "exact")
    return EdgeMode::exact;
  throw InputError("--edges must be 'wall' (the default: edges read their walls' thickness) or "
                   "'exact' (also the inscribed sphere at the point: convex edges read thinner), "
                   "got '" + name + "'");
}

double part_h0(const geometry::MeshReport& report) {
  if (!(report.volume > 0.0 && report.area > 0.0))
    throw InputError("h0 cannot be taken from the part: its volume is " +
                     number_text(report.volume, 6) + "; give --h0");
  return 2.0 * report.volume / report.area;
}

void validate(const ThicknessOptions& given) {
  ThicknessOptions options = given;
  if (options.h0_from_part)
    options.solve.h0 = 1.0;  // checked once the part is read
  if (options.min_thickness &&
      !(std::isfinite(*options.min_thickness) && *options.min_thickness > 0.0))
    throw InputError("--min-thickness must be a positive length, got " +
                     number_text(*options.min_thickness, 6));
  if (options.max_thickness &&
      !(std::isfinite(*options.max_thickness) && *options.max_thickness > 0.0))
    throw InputError("--max-thickness must be a positive length, got " +
                     number_text(*options.max_thickness, 6));
  if (options.min_region_area &&
      !(std::isfinite(*options.min_region_area) && *options.min_region_area >= 0.0))
    throw InputError("--min-region-area must be an area >= 0, got " +
                     number_text(*options.min_region_area, 6));
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
