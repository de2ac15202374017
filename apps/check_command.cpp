#include "apps/check_command.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "apps/exit_codes.hpp"
#include "apps/progress_display.hpp"
#include "apps/report/mesh_report_json.hpp"
#include "apps/run_limits.hpp"
#include "apps/report_text.hpp"
#include "core/errors.hpp"
#include "geometry/mesh_preparation.hpp"

namespace bemshape::apps {
namespace {

using geometry::MeshProblem;
using geometry::MeshReport;

/// Runs shorter than this [s] show no progress: a check usually takes well under a second
/// (docs/usage.md), and only files of some 10⁵ triangles and more make it worth a display.
constexpr double kProgressAfterSeconds = 1.0;

struct CheckOptions {
  std::string input;
  std::string report_path;
  double weld_tolerance = geometry::kWeldRelativeTolerance;
  bool quiet = false;
};

void print_report(const MeshReport& r, std::ostream& out) {
  const Eigen::Vector3d extent = r.bounding_box.extent();
  const std::string unit = r.unit.empty() ? "file units" : r.unit;
  out << "bemshape check: " << r.source << '\n'
      << "  format          " << r.format << ", " << r.triangles_read << " triangles and "
      << r.vertices_read << " vertices read\n"
      << "  unit            "
      << (r.unit.empty() ? "not recorded in the file (lengths in file units)"
          : !r.converted_from.empty() ? r.unit + " (converted from " + r.converted_from + ")"
                                      : r.unit + " (as recorded in the file)")
      << '\n'
      << "  faces           " << r.faces << '\n'
      << "  vertices        " << r.vertices << '\n'
      << "  shells          " << r.shells << '\n'
      << "  cavities        " << r.cavities << '\n'
      << "  volume          " << number_text(r.volume, 6) << " (" << unit << "^3)\n"
      << "  area            " << number_text(r.area, 6) << " (" << unit << "^2)\n"
      << "  bounding box    " << point_text(r.bounding_box.min) << " to "
      << point_text(r.bounding_box.max) << ", size " << number_text(extent.x(), 6) << " x "
      << number_text(extent.y(), 6) << " x " << number_text(extent.z(), 6) << '\n'
      << "  weld tolerance  " << number_text(r.weld_tolerance, 6) << '\n';
  out << "problems:" << (r.problems.empty() ? " none\n" : "\n");
  for (const MeshProblem& p : r.problems)
    out << "  [" << problem_status_label(p.status) << "] "
        << (p.count > 0 ? p.describe() : p.what + ": " + p.consequence) << '\n';
  out << "repairs:" << (r.repairs.empty() ? " none\n" : "\n");
  for (const std::string& repair : r.repairs)
    out << "  - " << repair << '\n';
  out << "result: "
      << (!r.usable() ? "refused"
          : r.defects.empty()
              ? "usable"
              : "usable with " + std::to_string(r.defects.size()) + " defect region" +
                    (r.defects.size() == 1 ? "" : "s") +
                    " (the surface crosses itself there; measured as given, marked 'defect')")
      << '\n';
}

void run_check(const CheckOptions& options, int& exit_code) {
  if (!(options.weld_tolerance >= 0.0 && options.weld_tolerance < 1e-2))
    throw InputError("--weld-tolerance " + number_text(options.weld_tolerance, 6) +
                     " must be in [0, 0.01)");
  geometry::MeshPreparationOptions preparation;
  preparation.weld_relative_tolerance = options.weld_tolerance;
  ProgressDisplay display(options.quiet, kProgressAfterSeconds);
  const geometry::PreparedMesh prepared =
      geometry::inspect_mesh_file(options.input, preparation, display.callback());
  display.finish();
  print_report(prepared.report, std::cout);
  std::cout.flush();
  if (!options.report_path.empty()) {
    std::ofstream out(options.report_path);
    out << mesh_report_json(prepared.report).dump(2) << '\n';
    if (!out)
      throw InputError(options.report_path + ": cannot write the JSON report");
  }
  if (!prepared.report.usable())
    throw InputError(prepared.report.refusal_message());
  exit_code = kExitSuccess;
}

}  // namespace

void register_check_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<CheckOptions>();
  CLI::App* check = app.add_subcommand(
      "check",
      "Read a mesh file, validate it as the boundary of a solid, repair what is safely "
      "repairable (coincident vertices, degenerate and duplicate faces, orientation) and print "
      "the report: faces, vertices, shells, cavities, volume, area, bounding box (in the file's "
      "units), every problem found and every repair. Exit code 0 if the mesh is usable (also with "
      "defect regions, where it crosses itself and is measured as given), 2 if "
      "it is refused or unreadable.");
  check->add_option("INPUT", options->input,
                    "Mesh file: .stl (ASCII or binary), .obj, .off, .ply, .3mf")
      ->required();
  check->add_option("--report", options->report_path, "Also write the report as JSON to this file");
  check
      ->add_option("--weld-tolerance", options->weld_tolerance,
                   "Merge vertices closer than this fraction of the bounding-box diagonal")
      ->capture_default_str();
  check->add_flag("--quiet", options->quiet, "No progress on stderr (shown after a second)");
  add_timeout_option(*check);
  check->callback([options, &exit_code] { run_check(*options, exit_code); });
}

}  // namespace bemshape::apps
