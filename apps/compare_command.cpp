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

#include "analysis/compare_with_fem.hpp"
#include "analysis/stage_times.hpp"
#include "analysis/voxel_resolution.hpp"
#include "apps/exit_codes.hpp"
#include "apps/output/atomic_file.hpp"
#include "apps/progress_display.hpp"
#include "apps/report_text.hpp"
#include "apps/run_limits.hpp"
#include "apps/solver_mesh_options.hpp"
#include "apps/text_histogram.hpp"
#include "core/errors.hpp"

namespace bemshape::apps {
namespace {

namespace fs = std::filesystem;

using analysis::Difference;
using analysis::FemComparison;
using analysis::kDefaultMaxProbes;
using analysis::kMaxResolvedKappaCell;
using analysis::kProbeDepthCells;
using analysis::StageTimes;

/// Width of the fullest histogram bar [characters].
constexpr int kHistogramBarWidth = 40;

struct CompareOptions {
  std::string input;
  double cell = 0.0;
  std::optional<double> h0;
  double a = 0.2;
  std::optional<double> max_edge;
  std::optional<double> sharp_angle;  // empty: the solver mesh rule's default
  SolverChoiceText solver;  ///< --solver, --far-field, --tolerance
  long long max_probes = kDefaultMaxProbes;
  std::string report_path;
  int threads = 0;
  bool quiet = false;
  std::uint64_t max_memory_bytes = 0;  ///< --max-memory; 0: the machine's memory only
};

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

nlohmann::json report_json(const CompareOptions& options, const FemComparison& c,
                           const StageTimes& times) {
  const features::FeatureParameters& p = c.parameters;
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
            {"max_edge", c.boundary.max_edge},
            {"max_edge_rule", c.boundary.max_edge_rule},
            {"sharp_angle", options.sharp_angle.value_or(geometry::RemeshingOptions{}.sharp_angle_degrees)},
            {"max_probes", options.max_probes},
            {"probe_depth_cells", kProbeDepthCells},
            {"threads", omp_get_max_threads()},
            {"march", BEMSHAPE_ARCH_NAME}}},
          {"mesh",
           {{"input_faces", c.input.report.faces},
            {"input_vertices", c.input.report.vertices},
            {"solver_faces", c.boundary.solver_mesh.num_faces()},
            {"solver_vertices", c.boundary.solver_mesh.num_vertices()},
            {"solver_max_edge", c.boundary.solver_mesh.max_edge_length()}}},
          {"grid",
           {{"cells", {grid.cells[0], grid.cells[1], grid.cells[2]}},
            {"cell_size", grid.cell_size},
            {"origin", vec(grid.origin)},
            {"solid_cells", c.voxels.solid_cells},
            {"cg_iterations", c.fem_report.iterations},
            {"multigrid_levels", c.fem_report.multigrid_levels}}},
          {"bem",
           {{"method", c.boundary.solution.report.method},
            {"unknowns", c.boundary.solution.report.unknowns},
            {"residual", c.boundary.solution.report.residual}}},
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

void print_report(std::ostream& out, const CompareOptions& options, const FemComparison& c,
                  const StageTimes& times) {
  const features::FeatureParameters& p = c.parameters;
  const fem::VoxelGrid<3>& grid = c.voxels.grid;
  const double kappa_cell = p.kappa() * options.cell;
  out << "bemshape compare: " << options.input << "  (lengths in the input file's units)\n"
      << "  parameters   h0 " << number_text(p.h0, 6) << ", a " << number_text(p.a, 6) << ", kappa "
      << number_text(p.kappa(), 4) << "; cell " << number_text(options.cell, 6) << " (kappa*cell "
      << number_text(kappa_cell, 3) << "), max edge " << number_text(c.boundary.max_edge, 6) << " ("
      << c.boundary.max_edge_rule << ")\n"
      << "  BEM          " << c.input.report.faces << " input faces, "
      << c.boundary.solver_mesh.num_faces() << " solver faces (longest edge "
      << number_text(c.boundary.solver_mesh.max_edge_length(), 4) << "), "
      << c.boundary.solution.report.method << '\n'
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
  analysis::CompareOptions job;
  job.solve = solve_options(options.h0.value_or(0.0), options.a, options.max_edge,
                            options.sharp_angle, options.solver, options.max_memory_bytes);
  job.h0_follows_cell = !options.h0;
  job.cell = options.cell;
  job.max_probes = options.max_probes;
  analysis::comparison_parameters(job);  // --cell, --max-probes, h0 and a, before the rest
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
  const FemComparison c =
      analysis::compare_with_fem(fs::path(options.input), job, display.callback());
  times.add(c.times);
  display.finish();

  if (!options.report_path.empty())
    output::write_file_atomically(options.report_path,
                                  report_json(options, c, times).dump(2) + '\n');
  print_report(std::cout, options, c, times);
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
  cmd->add_option("INPUT", options->input,
                  "Mesh file: .stl (ASCII or binary), .obj, .off, .ply, .3mf")
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
