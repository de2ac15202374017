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

#include "apps/boundary_solve.hpp"
#include "apps/exit_codes.hpp"
#include "apps/output/csv_writer.hpp"
#include "apps/output/vti_writer.hpp"
#include "apps/point_table.hpp"
#include "apps/progress_display.hpp"
#include "apps/report_text.hpp"
#include "apps/run_limits.hpp"
#include "apps/solver_mesh_options.hpp"
#include "apps/stage_times.hpp"
#include "bem/evaluate/potential_evaluation.hpp"
#include "core/errors.hpp"
#include "features/point_features.hpp"

namespace bemshape::apps {
namespace {

namespace fs = std::filesystem;

/// Largest number of evaluation points accepted. The treecode of bem::evaluate_potential
/// costs about 1.2 ms of CPU per point on a 20,000-face part (docs/benchmarks.md,
/// "Interior evaluation at many points"): 10⁶ points are about ten minutes on two free cores —
/// beyond that a coarser grid answers sooner.
constexpr double kMaxPoints = 1.0e6;

struct FeaturesOptions {
  SolverChoice solver;  ///< --solver, --tolerance
  std::string input;
  std::string points_path;
  std::optional<double> grid_spacing;
  std::string output;
  std::optional<double> h0;
  double a = 0.2;
  std::optional<double> max_edge;
  double sharp_angle = geometry::RemeshingOptions{}.sharp_angle_degrees;
  std::optional<double> skeleton_width;
  int threads = 0;
  bool quiet = false;
  std::uint64_t max_memory_bytes = 0;
};

/// Node grid over a bounding box: nodes at origin + i·spacing, symmetric about the box centre
/// and covering the box with at most one spacing to spare on each side.
output::ImageGrid grid_over(const geometry::BoundingBox& box, double spacing) {
  output::ImageGrid grid;
  const Eigen::Vector3d centre = 0.5 * (box.min + box.max), extent = box.extent();
  for (int d = 0; d < 3; ++d) {
    grid.cells[d] = static_cast<long long>(std::ceil(extent(d) / spacing)) + 1;
    grid.spacing[d] = spacing;
    grid.origin[d] = centre(d) - 0.5 * spacing * double(grid.cells[d]);
  }
  return grid;
}

double point_count(const output::ImageGrid& grid) {
  return double(grid.cells[0] + 1) * double(grid.cells[1] + 1) * double(grid.cells[2] + 1);
}

/// Grid nodes, x fastest, then y, then z (VTK point order).
Eigen::MatrixX3d grid_points(const output::ImageGrid& grid) {
  const long long nx = grid.cells[0] + 1, ny = grid.cells[1] + 1, nz = grid.cells[2] + 1;
  Eigen::MatrixX3d points(nx * ny * nz, 3);
  Eigen::Index row = 0;
  for (long long k = 0; k < nz; ++k)
    for (long long j = 0; j < ny; ++j)
      for (long long i = 0; i < nx; ++i, ++row)
        points.row(row) << grid.origin[0] + double(i) * grid.spacing[0],
            grid.origin[1] + double(j) * grid.spacing[1],
            grid.origin[2] + double(k) * grid.spacing[2];
  return points;
}

void refuse_large_grid(const FeaturesOptions& options, const geometry::PreparedMesh& input) {
  const double spacing = *options.grid_spacing;
  const output::ImageGrid grid = grid_over(input.report.bounding_box, spacing);
  const double count = point_count(grid);
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
  if (!options.output.empty()) {
    const fs::path folder = fs::path(options.output).parent_path();
    if (!folder.empty() && !fs::is_directory(folder))
      throw InputError(options.output + ": the folder of -o does not exist");
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
  BoundarySolveSetup setup;
  setup.input = options.input;
  setup.h0 = *options.h0;
  setup.a = options.a;
  setup.max_edge = options.max_edge;
  setup.sharp_angle_degrees = options.sharp_angle;
  setup.solver = options.solver;
  setup.max_memory_bytes = options.max_memory_bytes;
  if (grid_mode)
    setup.check_input = [&options](const geometry::PreparedMesh& input) {
      refuse_large_grid(options, input);
      return std::uint64_t{0};  // the grid's points are allocated after the solve
    };
  const BoundarySolveRun run = prepare_and_solve(setup, times, display.callback());

  output::ImageGrid grid;
  if (grid_mode) {
    grid = grid_over(run.input.report.bounding_box, *options.grid_spacing);
    points = grid_points(grid);
  }
  report_progress(display.callback(), "evaluate", 0.0);
  const bem::PotentialField field = times.time("evaluate", [&] {
    // The treecode's error tracks the solver's: no larger than the residual asked for.
    bem::PotentialEvaluationOptions evaluation;
    evaluation.treecode = bem::LaplaceTreecodeParameters::for_tolerance(options.solver.tolerance);
    return bem::evaluate_potential(run.solver_mesh, run.solution, points, display.callback(),
                                   evaluation);
  });
  features::FeatureParameters parameters;
  parameters.h0 = *options.h0;
  parameters.a = options.a;
  parameters.skeleton_width =
      options.skeleton_width.value_or(grid_mode ? *options.grid_spacing : run.max_edge);
  report_progress(display.callback(), "features", 0.0);
  const features::FeatureField<3> f = times.time("features", [&] {
    return features::compute_features<3>(field.s, field.gradient, field.inside, parameters);
  });

  const Eigen::Index np = points.rows();
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
    rows << points, inside, field.s, f.f_h, f.h_f, f.h_p, f.n_f, skeleton;
    const std::vector<std::string> header{"x",   "y",   "z",   "inside", "s_x", "s_y", "s_z",
                                          "f_h", "h_f", "h_p", "n_x",    "n_y", "n_z", "skeleton"};
    if (options.output.empty())
      std::cout << output::format_csv(header, rows) << std::flush;
    else
      output::write_csv(options.output, header, rows);
  });
  display.finish();
  // h_f and h_p are clamped to 0 where the inverse thickness exceeds 1/a
  // (features/thickness.hpp): a wall thinner than zero, which only the discretisation
  // produces. Counted so that a 0 in the output is not taken for a measured wall.
  Eigen::Index clamped = 0;
  for (Eigen::Index p = 0; p < np; ++p)
    if (field.inside[static_cast<std::size_t>(p)] && (f.h_f(p) == 0.0 || f.h_p(p) == 0.0))
      ++clamped;
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
              << "  mesh         " << run.input.report.faces << " input faces, "
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
  cmd->add_option("INPUT", options->input, "Mesh file: .stl (ASCII or binary), .obj, .off, .ply")
      ->required();
  cmd->add_option("--points", options->points_path,
                  "Text/CSV file of points x,y,z (one per line, optional header)");
  cmd->add_option("--grid", options->grid_spacing,
                  "Evaluate on a regular grid of this spacing over the bounding box");
  cmd->add_option("-o,--output", options->output,
                  "Output: .csv (one row per point; stdout if omitted) or .vti (--grid only)");
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
