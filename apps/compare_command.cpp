#include "apps/compare_command.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/boundary_solve.hpp"
#include "apps/exit_codes.hpp"
#include "apps/fem_command.hpp"
#include "apps/output/atomic_file.hpp"
#include "apps/progress_display.hpp"
#include "apps/report_text.hpp"
#include "apps/run_limits.hpp"
#include "apps/solver_mesh_options.hpp"
#include "apps/stage_times.hpp"
#include "apps/text_histogram.hpp"
#include "apps/thickness_statistics.hpp"
#include "apps/voxel_memory_check.hpp"
#include "bem/evaluate/potential_evaluation.hpp"
#include "core/errors.hpp"
#include "features/point_features.hpp"
#include "features/thickness.hpp"
#include "fem/characteristic_function.hpp"
#include "fem/shape_feature_solver.hpp"
#include "fem/voxel_features.hpp"
#include "geometry/closest_point.hpp"

namespace bemshape::apps {
namespace {

namespace fs = std::filesystem;

/// Probes lie at least this many cells from the surface. Within a cell or two of it the FEM
/// sees the staircase of its voxels instead of the surface and its ∇s is a difference
/// quotient across the jump of χ; two cells is where both methods describe the same solid.
constexpr double kProbeDepthCells = 2.0;
/// Default cap on the probes. The BEM evaluates each probe against every solver face (two
/// kernels, Laplace and Yukawa): 2000 probes on the 1280-face ball take 8–20 s on two busy
/// cores, about as long as its dense solve, and the median and 95th percentile of 2000
/// samples are stable to a few per cent of their value. Probes within a panel diameter of
/// the surface cost several times more (near-surface interpolation, polar quadrature): on
/// thin walls meshed coarsely, use fewer (docs/usage.md).
constexpr long long kDefaultMaxProbes = 2000;
/// Bins of the h_p histogram on stdout.
constexpr int kHistogramBins = 12;
/// Width of the fullest histogram bar [characters].
constexpr int kHistogramBarWidth = 40;

struct CompareOptions {
  std::string input;
  double cell = 0.0;
  std::optional<double> h0;
  double a = 0.2;
  std::optional<double> max_edge;
  double sharp_angle = geometry::RemeshingOptions{}.sharp_angle_degrees;
  SolverChoice solver;  ///< --solver, --tolerance
  long long max_probes = kDefaultMaxProbes;
  std::string report_path;
  int threads = 0;
  bool quiet = false;
  std::uint64_t max_memory_bytes = 0;  ///< --max-memory; 0: the machine's memory only
};

/// The voxel side of the comparison, built right after the input is read (so that a cell
/// too coarse for any probe is refused before the BEM solve).
struct VoxelSide {
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
  long long left_out = 0;  ///< probes not measurable by either method (h_p saturated)
};

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
VoxelSide voxelise_and_pick_probes(const CompareOptions& options, const geometry::SurfaceMesh& mesh,
                                   const features::FeatureParameters& parameters,
                                   StageTimes& times) {
  VoxelSide side;
  const VoxelMemoryBudget budget{options.input, options.cell, options.h0.has_value(),
                                 options.max_memory_bytes};
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
    throw InputError(options.input + ": no probe point: none of the " +
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

nlohmann::json vec(const Eigen::Vector3d& p) {
  return nlohmann::json::array({p.x(), p.y(), p.z()});
}

nlohmann::json difference_json(const Difference& d) {
  return {{"median", d.median},
          {"p95", d.p95},
          {"max", d.max},
          {"max_location", vec(d.max_location)},
          {"median_signed", d.median_signed},
          {"probes", d.relative.size()},
          {"left_out", d.left_out}};
}

struct Comparison {
  BoundarySolveRun run;
  VoxelSide voxels;
  fem::FemSolveReport fem_report;
  long long outside_bem = 0;  ///< probes the BEM's winding number puts outside
  Difference f_h, h_p;
  Histogram h_p_histogram;
};

nlohmann::json report_json(const CompareOptions& options, const features::FeatureParameters& p,
                           const Comparison& c, const StageTimes& times) {
  const fem::VoxelGrid<3>& grid = c.voxels.grid;
  nlohmann::json timing = nlohmann::json::object();
  for (const auto& [stage, seconds] : times.stages())
    timing[stage] = seconds;
  timing["total"] = times.elapsed();
  return {{"bemshape", BEMSHAPE_VERSION},
          {"command", "compare"},
          {"input", options.input},
          {"units", "lengths in the input file's units; differences as fractions"},
          {"parameters",
           {{"h0", p.h0},
            {"a", p.a},
            {"kappa", p.kappa()},
            {"cell", options.cell},
            {"kappa_cell", p.kappa() * options.cell},
            {"max_edge", c.run.max_edge},
            {"max_edge_rule", c.run.max_edge_rule},
            {"sharp_angle", options.sharp_angle},
            {"max_probes", options.max_probes},
            {"probe_depth_cells", kProbeDepthCells},
            {"threads", omp_get_max_threads()},
            {"march", BEMSHAPE_ARCH_NAME}}},
          {"mesh",
           {{"input_faces", c.run.input.report.faces},
            {"input_vertices", c.run.input.report.vertices},
            {"solver_faces", c.run.solver_mesh.num_faces()},
            {"solver_vertices", c.run.solver_mesh.num_vertices()},
            {"solver_max_edge", c.run.solver_mesh.max_edge_length()}}},
          {"grid",
           {{"cells", {grid.cells[0], grid.cells[1], grid.cells[2]}},
            {"cell_size", grid.cell_size},
            {"origin", vec(grid.origin)},
            {"solid_cells", c.voxels.solid_cells},
            {"cg_iterations", c.fem_report.iterations},
            {"multigrid_levels", c.fem_report.multigrid_levels}}},
          {"bem",
           {{"method", c.run.solution.report.method},
            {"unknowns", c.run.solution.report.unknowns},
            {"residual", c.run.solution.report.residual}}},
          {"probes",
           {{"count", c.voxels.probes.rows()},
            {"candidates", c.voxels.deep_cells},
            {"min_depth", kProbeDepthCells * options.cell},
            {"outside_bem", c.outside_bem}}},
          {"difference",
           {{"definition", "|FEM - BEM| / |BEM| at each probe"},
            {"f_h", difference_json(c.f_h)},
            {"h_p", difference_json(c.h_p)}}},
          {"histogram",
           {{"h_p", {{"edges", c.h_p_histogram.edges}, {"counts", c.h_p_histogram.counts}}}}},
          {"timing", timing}};
}

std::string percent(double fraction) {
  return number_text(100.0 * fraction, 3) + "%";
}

void print_difference(std::ostream& out, const char* name, const Difference& d) {
  out << "               " << name << "  median " << percent(d.median) << ", p95 " << percent(d.p95)
      << ", max " << percent(d.max) << " at " << point_text(d.max_location)
      << "; median of (FEM - BEM)/BEM " << (d.median_signed >= 0.0 ? "+" : "")
      << percent(d.median_signed) << '\n';
  if (d.left_out > 0)
    out << "               (" << d.left_out << " probes left out: " << name
        << " not measurable, no opposite wall within reach of h0)\n";
}

void print_report(std::ostream& out, const CompareOptions& options,
                  const features::FeatureParameters& p, const Comparison& c,
                  const StageTimes& times) {
  const fem::VoxelGrid<3>& grid = c.voxels.grid;
  const double kappa_cell = p.kappa() * options.cell;
  out << "bemshape compare: " << options.input << "  (lengths in the input file's units)\n"
      << "  parameters   h0 " << number_text(p.h0, 6) << ", a " << number_text(p.a, 6) << ", kappa "
      << number_text(p.kappa(), 4) << "; cell " << number_text(options.cell, 6) << " (kappa*cell "
      << number_text(kappa_cell, 3) << "), max edge " << number_text(c.run.max_edge, 6) << " ("
      << c.run.max_edge_rule << ")\n"
      << "  BEM          " << c.run.input.report.faces << " input faces, "
      << c.run.solver_mesh.num_faces() << " solver faces (longest edge "
      << number_text(c.run.solver_mesh.max_edge_length(), 4) << "), "
      << c.run.solution.report.method << '\n'
      << "  FEM          grid " << grid.cells[0] << " x " << grid.cells[1] << " x " << grid.cells[2]
      << " cells of " << number_text(grid.cell_size, 6) << ", " << c.voxels.solid_cells
      << " solid, " << c.fem_report.iterations << " CG iterations, "
      << c.fem_report.multigrid_levels << " multigrid levels\n"
      << "  probes       " << c.voxels.probes.rows() << " of the " << c.voxels.deep_cells
      << " solid cell centres at least " << number_text(kProbeDepthCells, 2) << " cells ("
      << number_text(kProbeDepthCells * options.cell, 4) << ") from the surface";
  if (c.outside_bem > 0)
    out << "; " << c.outside_bem << " of them outside the BEM's solver mesh, left out";
  out << "\n  difference   |FEM - BEM| / |BEM| at the probes\n";
  print_difference(out, "f_h", c.f_h);
  print_difference(out, "h_p", c.h_p);
  out << "  h_p difference, probes per bin:\n"
      << format_histogram(c.h_p_histogram, 100.0, "%", kHistogramBarWidth, "    ")
      << "  timing      ";
  for (const auto& [stage, seconds] : times.stages())
    out << ' ' << stage << ' ' << number_text(seconds, 3) << " s,";
  out << " total " << number_text(times.elapsed(), 3) << " s\n";
  if (kappa_cell > kMaxResolvedKappaCell)
    out << "  note         kappa*cell = " << number_text(kappa_cell, 3) << " > "
        << number_text(kMaxResolvedKappaCell, 2)
        << ": the FEM under-resolves the boundary layer of s (differences of several %); "
           "--cell "
        << number_text(kMaxResolvedKappaCell / p.kappa(), 3) << " or smaller resolves it\n";
  if (!options.report_path.empty())
    out << "  report       " << options.report_path << '\n';
}

void run_compare(const CompareOptions& options, int& exit_code) {
  StageTimes times;
  if (!(std::isfinite(options.cell) && options.cell > 0.0))
    throw InputError("--cell must be a positive length, got " + number_text(options.cell, 4));
  if (options.max_probes < 1)
    throw InputError("--max-probes must be at least 1, got " + std::to_string(options.max_probes));
  features::FeatureParameters parameters;
  parameters.h0 = options.h0.value_or(kDefaultH0Cells * options.cell);
  parameters.a = options.a;
  parameters.skeleton_width = options.cell;
  features::validate(parameters);
  if (!options.report_path.empty()) {
    const fs::path folder = fs::path(options.report_path).parent_path();
    if (!folder.empty() && !fs::is_directory(folder))
      throw InputError(options.report_path + ": the folder of --report does not exist");
  }
  if (options.threads < 0)
    throw InputError("--threads must be positive, got " + std::to_string(options.threads));
  if (options.threads > 0)
    omp_set_num_threads(options.threads);

  ProgressDisplay display(options.quiet);
  Comparison c;
  BoundarySolveSetup setup;
  setup.input = options.input;
  setup.h0 = parameters.h0;
  setup.a = parameters.a;
  setup.max_edge = options.max_edge;
  setup.sharp_angle_degrees = options.sharp_angle;
  setup.solver = options.solver;
  setup.max_memory_bytes = options.max_memory_bytes;
  setup.check_input = [&](const geometry::PreparedMesh& input) {
    report_progress(display.callback(), "voxelise", 0.0);
    c.voxels = voxelise_and_pick_probes(options, input.mesh, parameters, times);
    // The two solves run one after the other, each within --max-memory, but the grid's χ
    // stays allocated through the BEM solve.
    return static_cast<std::uint64_t>(c.voxels.grid.chi.size() * sizeof(float));
  };
  c.run = prepare_and_solve(setup, times, display.callback());

  report_progress(display.callback(), "fem solve", 0.0);
  const fem::FemSolution<3> fem_solution = times.time("fem_solve", [&] {
    return fem::solve_shape_feature_pde<3>(c.voxels.grid, parameters, {}, display.callback());
  });
  c.fem_report = fem_solution.report;
  report_progress(display.callback(), "fem features", 0.0);
  const fem::VoxelFeatures<3> fem_features = times.time("fem_features", [&] {
    return fem::voxel_features<3>(c.voxels.grid, fem_solution.s, parameters);
  });

  report_progress(display.callback(), "evaluate", 0.0);
  const bem::PotentialField field = times.time("evaluate", [&] {
    return bem::evaluate_potential(c.run.solver_mesh, c.run.solution, c.voxels.probes,
                                   display.callback());
  });
  const features::FeatureField<3> bem_features = times.time("features", [&] {
    return features::compute_features<3>(field.s, field.gradient, field.inside, parameters);
  });
  display.finish();

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
    throw InputError(options.input + ": h_p is not measurable at any of the " + std::to_string(np) +
                     " probes (no opposite wall within reach of h0 = " +
                     number_text(parameters.h0, 4) + "); use a larger --h0");
  c.h_p_histogram = histogram(c.h_p.relative, kHistogramBins);

  if (!options.report_path.empty())
    output::write_file_atomically(options.report_path,
                                  report_json(options, parameters, c, times).dump(2) + '\n');
  print_report(std::cout, options, parameters, c, times);
  std::cout.flush();
  exit_code = kExitSuccess;
}

}  // namespace

void register_compare_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Solve one part by the BEM and by the voxel FEM with the same parameters and report the "
      "relative differences of f_h and h_p at interior probe points (FEM cell centres at least "
      "two cells from the surface). Lengths in the input file's units.");
  cmd->add_option("INPUT", options->input, "Mesh file: .stl (ASCII or binary), .obj, .off, .ply")
      ->required();
  cmd->add_option("--cell", options->cell, "FEM grid cell size, in file units")->required();
  cmd->add_option("--h0", options->h0,
                  "Characteristic length: about the smallest wall thickness of interest "
                  "(default 20 cells)");
  cmd->add_option("--a", options->a, "Dimensionless diffusion parameter a of the PDE")
      ->capture_default_str();
  add_solver_mesh_options(*cmd, options->max_edge, options->sharp_angle);
  add_solver_choice_options(*cmd, options->solver);
  cmd->add_option("--max-probes", options->max_probes,
                  "At most this many probe points, spread evenly over the eligible cell centres "
                  "(each costs one BEM evaluation per solver face)")
      ->capture_default_str();
  cmd->add_option("--report", options->report_path, "Also write the report as JSON to this file");
  cmd->add_option("--threads", options->threads, "Number of threads (default: all cores)");
  cmd->add_flag("--quiet", options->quiet, "No progress on stderr");
  add_timeout_option(*cmd);
  add_max_memory_option(*cmd, options->max_memory_bytes);
  cmd->callback([options, &exit_code] { run_compare(*options, exit_code); });
}

}  // namespace bemshape::apps
