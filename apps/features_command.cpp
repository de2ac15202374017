#include "apps/features_command.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "analysis/measure_features.hpp"
#include "analysis/stage_times.hpp"
#include "apps/exit_codes.hpp"
#include "apps/output/atomic_file.hpp"
#include "apps/output/csv_writer.hpp"
#include "apps/output/vti_writer.hpp"
#include "apps/point_table.hpp"
#include "apps/progress_display.hpp"
#include "apps/report/features_report_json.hpp"
#include "apps/report_text.hpp"
#include "apps/run_limits.hpp"
#include "apps/solver_mesh_options.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"

namespace bemshape::apps {
namespace {

namespace fs = std::filesystem;

using analysis::kMaxPoints;
using analysis::StageTimes;

struct FeaturesOptions {
  SolverChoiceText solver;  ///< --solver, --far-field, --tolerance
  std::string input;
  std::string points_path;
  std::optional<double> grid_spacing;
  std::string output;
  std::string report_path;
  std::optional<double> h0;
  double a = 0.2;
  std::optional<double> max_edge;
  std::optional<double> sharp_angle;  // empty: the solver mesh rule's default
  std::optional<double> skeleton_width;
  int threads = 0;
  bool quiet = false;
  std::uint64_t max_memory_bytes = 0;
};

/// The grid as the VTK ImageData writer takes it.
output::ImageGrid image_grid(const analysis::PointGrid& grid) {
  output::ImageGrid image;
  for (int d = 0; d < 3; ++d) {
    image.cells[d] = grid.cells[d];
    image.origin[d] = grid.origin[d];
    image.spacing[d] = grid.spacing[d];
  }
  return image;
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void run_features(const FeaturesOptions& options, int& exit_code) {
  StageTimes times;
  const bool grid_mode = options.grid_spacing.has_value();
  if (grid_mode == !options.points_path.empty())
    throw InputError(
        "give exactly one of --points PTS.csv (points of interest) and --grid "
        "SPACING (a regular grid over the part's bounding box)");
  if (grid_mode && !(std::isfinite(*options.grid_spacing) && *options.grid_spacing > 0.0))
    throw InputError("--grid must be a positive spacing, got " +
                     number_text(*options.grid_spacing, 4));
  if (!options.h0)
    throw InputError(
        "--h0 is required: choose about the smallest wall thickness of interest, in "
        "the input file's units (e.g. --h0 2 for 2 mm walls in a file in mm)");
  if (options.skeleton_width && !(*options.skeleton_width >= 0.0))
    throw InputError("--skeleton-width must be a non-negative length");
  const std::string ext = lower_extension(options.output);
  if (!options.output.empty() && ext != ".csv" && ext != ".vti")
    throw InputError(options.output + ": unknown output format '" + ext +
                     "'; supported: .csv (one row per point), .vti (VTK ImageData, --grid only)");
  if (ext == ".vti" && !grid_mode)
    throw InputError(options.output + ": .vti output needs --grid (scattered --points go to .csv)");
  for (const auto& [path, option] : {std::pair{&options.output, "-o"},
                                     std::pair{&options.report_path, "--report"}}) {
    const fs::path folder = fs::path(*path).parent_path();
    if (!path->empty() && !folder.empty() && !fs::is_directory(folder))
      throw InputError(*path + ": the folder of " + option + " does not exist");
  }
  if (options.threads < 0)
    throw InputError("--threads must be positive, got " + std::to_string(options.threads));
  if (options.threads > 0)
    omp_set_num_threads(options.threads);
  Eigen::MatrixX3d points;
  if (!grid_mode)
    points = times.time("read_points", [&] { return read_points(options.points_path); });
  if (!grid_mode && double(points.rows()) > kMaxPoints)
    throw ResourceError(options.points_path + ": " + std::to_string(points.rows()) +
                        " points, more than the limit of " + number_text(kMaxPoints, 4) +
                        "; split the file into smaller batches");

  ProgressDisplay display(options.quiet);
  analysis::FeaturesOptions job;
  job.solve = solve_options(*options.h0, options.a, options.max_edge, options.sharp_angle,
                            options.solver, options.max_memory_bytes);
  job.skeleton_width = options.skeleton_width;
  const fs::path input(options.input);
  const analysis::FeaturesResult result =
      grid_mode ? analysis::measure_features_on_grid(input, *options.grid_spacing, job,
                                                     display.callback())
                : analysis::measure_features(input, points, job, display.callback());
  points = Eigen::MatrixX3d();  // the result holds them
  times.add(result.times);
  const analysis::BoundarySolve& run = result.boundary;
  const bem::PotentialField& field = result.field;
  const features::FeatureField<3>& f = result.features;
  const features::FeatureParameters& parameters = result.parameters;
  const output::ImageGrid grid = grid_mode ? image_grid(*result.grid) : output::ImageGrid{};
  const Eigen::MatrixX3d& at = result.points;

  const Eigen::Index np = at.rows();
  Eigen::VectorXd inside(np), skeleton(np);
  for (Eigen::Index p = 0; p < np; ++p) {
    inside(p) = field.inside[static_cast<std::size_t>(p)] ? 1.0 : 0.0;
    skeleton(p) = f.skeleton[static_cast<std::size_t>(p)] ? 1.0 : 0.0;
  }
  times.time("write", [&] {
    if (ext == ".vti") {
      const Eigen::MatrixXd chi = inside, s = field.s, fh = f.f_h, hf = f.h_f, hp = f.h_p,
                            nf = f.n_f, sk = skeleton;
      using Location = output::ImageField::Location;
      output::write_vti(options.output, grid,
                        {{"inside", Location::point, &chi},
                         {"s", Location::point, &s},
                         {"f_h", Location::point, &fh},
                         {"h_f", Location::point, &hf},
                         {"h_p", Location::point, &hp},
                         {"n_f", Location::point, &nf},
                         {"skeleton", Location::point, &sk}});
      return;
    }
    Eigen::MatrixXd rows(np, 14);
    rows << at, inside, field.s, f.f_h, f.h_f, f.h_p, f.n_f, skeleton;
    const std::vector<std::string> header{"x",   "y",   "z",   "inside", "s_x", "s_y", "s_z",
                                          "f_h", "h_f", "h_p", "n_x",    "n_y", "n_z", "skeleton"};
    if (options.output.empty())
      std::cout << output::format_csv(header, rows) << std::flush;
    else
      output::write_csv(options.output, header, rows);
  });
  display.finish();
  if (!options.report_path.empty()) {
    const RunFigures figures{omp_get_max_threads(), double(peak_resident_bytes()) / 1e6};
    const std::optional<std::string> output =
        options.output.empty() ? std::nullopt : std::optional<std::string>(options.output);
    output::write_file_atomically(
        options.report_path,
        features_report_json(job, result, options.input, output, times, figures).dump(2) + '\n');
  }
  // h_f and h_p are clamped to 0 where the inverse thickness exceeds 1/a
  // (features/thickness.hpp): counted so that a 0 in the output is not taken for a wall.
  const Eigen::Index clamped = result.clamped_points;
  const auto warn_clamped = [&](std::ostream& out) {
    if (clamped == 0)
      return;
    out << "  warning      h_f or h_p clamped to 0 at " << clamped << " inside point"
        << (clamped == 1 ? "" : "s") << ", where the inverse thickness exceeded 1/a:\n"
        << "               only discretisation error produces that (points within about an\n"
        << "               element of the surface, or h0 far above the walls' thickness); try a\n"
        << "               smaller --max-edge, or an h0 nearer the walls' thickness\n";
  };
  if (options.output.empty())
    warn_clamped(std::cerr);  // stdout holds the CSV
  if (!options.output.empty()) {
    const auto inside_count = static_cast<long long>(inside.sum());
    std::cout << "bemshape features: " << options.input << "  (lengths in the input file's units)\n"
              << "  parameters   h0 " << number_text(*options.h0, 4) << ", a "
              << number_text(options.a, 4) << ", max edge " << number_text(run.max_edge, 4) << " ("
              << run.max_edge_rule << "), skeleton width "
              << number_text(parameters.skeleton_width, 4) << '\n'
              << "  mesh         " << result.input.report.faces << " input faces, "
              << run.solver_mesh.num_faces() << " solver faces\n"
              << "  points       " << np << " (" << inside_count << " inside)";
    if (grid_mode)
      std::cout << ", grid " << grid.cells[0] + 1 << " x " << grid.cells[1] + 1 << " x "
                << grid.cells[2] + 1 << " spacing " << number_text(*options.grid_spacing, 4);
    std::cout << "\n  timing      ";
    for (const auto& [stage, seconds] : times.stages())
      std::cout << ' ' << stage << ' ' << number_text(seconds, 4) << " s,";
    std::cout << " total " << number_text(times.elapsed(), 4) << " s\n"
              << "  output       " << options.output << '\n';
    warn_clamped(std::cout);
  }
  exit_code = kExitSuccess;
}

}  // namespace

void register_features_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<FeaturesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "features",
      "Shape features inside a solid part at given points or on a regular grid (no volume "
      "mesh): inside flag, s, f_h, h_f, h_p, n_f, skeleton. Lengths in the input file's units.");
  cmd->add_option("INPUT", options->input,
                  "Mesh file: .stl (ASCII or binary), .obj, .off, .ply, .3mf")
      ->required();
  cmd->add_option("--points", options->points_path,
                  "Text/CSV file of points x,y,z (one per line, optional header)");
  cmd->add_option("--grid", options->grid_spacing,
                  "Evaluate on a regular grid of this spacing over the bounding box");
  cmd->add_option("-o,--output", options->output,
                  "Output: .csv (one row per point; stdout if omitted) or .vti (--grid only)");
  cmd->add_option("--report", options->report_path,
                  "Also write a JSON report (parameters, points inside, range of h_f and h_p, "
                  "solver, timing) to this file");
  cmd->add_option("--h0", options->h0,
                  "Characteristic length: about the smallest wall thickness of interest")
      ->required();
  cmd->add_option("--a", options->a, "Dimensionless diffusion parameter a of the PDE")
      ->capture_default_str();
  add_solver_mesh_options(*cmd, options->max_edge, options->sharp_angle);
  add_solver_choice_options(*cmd, options->solver);
  cmd->add_option("--skeleton-width", options->skeleton_width,
                  "Half-width of the skeleton band (default: grid spacing, or the element size)");
  cmd->add_option("--threads", options->threads, "Number of threads (default: all cores)");
  cmd->add_flag("--quiet", options->quiet, "No progress on stderr");
  add_max_memory_option(*cmd, options->max_memory_bytes);
  add_timeout_option(*cmd);
  cmd->callback([options, &exit_code] { run_features(*options, exit_code); });
}

}  // namespace bemshape::apps
