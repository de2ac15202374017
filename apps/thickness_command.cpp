#include "apps/thickness_command.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "analysis/area_histogram.hpp"
#include "analysis/measure_thickness.hpp"
#include "analysis/stage_times.hpp"
#include "apps/exit_codes.hpp"
#include "apps/output/atomic_file.hpp"
#include "apps/output/csv_writer.hpp"
#include "apps/output/ply_writer.hpp"
#include "apps/output/vtp_writer.hpp"
#include "apps/progress_display.hpp"
#include "apps/report/thickness_report_json.hpp"
#include "apps/report/units_check.hpp"
#include "apps/report_text.hpp"
#include "apps/run_limits.hpp"
#include "apps/solver_mesh_options.hpp"
#include "apps/text_histogram.hpp"
#include "apps/thickness_html_report.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"
#include "features/thickness.hpp"

namespace bemshape::apps {
namespace {

namespace fs = std::filesystem;
using analysis::kColumnFh;
using analysis::kColumnHf;
using analysis::kColumnHp;
using analysis::kColumnNf;
using analysis::kColumnWall;
using analysis::ThickRegion;
using analysis::StageTimes;
using analysis::SurfaceFeatures;
using analysis::ThicknessResult;
using analysis::ThicknessStatistics;
using analysis::ThinRegion;

struct ThicknessOptions {
  SolverChoiceText solver;  ///< --solver, --far-field, --tolerance
  std::string input;
  std::optional<double> h0;
  double a = 0.2;
  std::string measure = "wall";
  std::string edges = "wall";
  std::optional<double> min_thickness;
  std::optional<double> max_thickness;
  std::optional<double> min_region_area;
  std::string units_check = "on";
  std::optional<double> max_edge;
  std::optional<double> sharp_angle;  // empty: the solver mesh rule's default
  std::string output;
  std::string solver_output;
  std::string report_path;
  std::string html_path;
  int threads = 0;
  bool quiet = false;
  std::uint64_t max_memory_bytes = 0;
  bool fit_memory = false;  // --fit-memory
};

enum class OutputFormat { none, vtp, ply, csv };

std::string seconds_text(double seconds) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", seconds);
  return buffer;
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// The output format, decided before any work so a typo does not cost a solve.
OutputFormat output_format(const std::string& path) {
  if (path.empty())
    return OutputFormat::none;
  const std::string ext = lower_extension(path);
  if (ext == ".vtp")
    return OutputFormat::vtp;
  if (ext == ".ply")
    return OutputFormat::ply;
  if (ext == ".csv")
    return OutputFormat::csv;
  throw InputError(path + ": unknown output format '" + ext +
                   "'; supported: .vtp (VTK PolyData for ParaView), .ply (binary, vertex colours), "
                   ".csv (one row per vertex)");
}

void require_writable_folder(const std::string& path, const char* option) {
  if (path.empty())
    return;
  const fs::path folder = fs::path(path).parent_path();
  if (!folder.empty() && !fs::is_directory(folder))
    throw InputError(path + ": the folder of " + option + " does not exist");
}

/// 1 for every vertex of a face with faces[f] != 0.
std::vector<char> vertex_flags(const geometry::SurfaceMesh& mesh, const std::vector<char>& faces) {
  std::vector<char> flags(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
    if (faces[static_cast<std::size_t>(f)] != 0)
      for (int k = 0; k < 3; ++k)
        flags[static_cast<std::size_t>(mesh.faces()(f, k))] = 1;
  return flags;
}

Eigen::MatrixXd as_column(const std::vector<char>& flags) {
  Eigen::MatrixXd column(static_cast<Eigen::Index>(flags.size()), 1);
  for (std::size_t i = 0; i < flags.size(); ++i)
    column(static_cast<Eigen::Index>(i), 0) = flags[i] != 0 ? 1.0 : 0.0;
  return column;
}

/// Writes `v` (features on `mesh`) to `path` in `format`. `defect_faces` (#F of `mesh`, or
/// empty when the input has no defect region) adds the field `defect`: 1 on the faces within
/// h0 of a region where the surface crosses itself and was measured as given, and on their
/// vertices.
void write_output(const std::string& path, OutputFormat format, const geometry::SurfaceMesh& mesh,
                  const SurfaceFeatures& v, const ThicknessResult& result,
                  const std::vector<char>& defect_faces) {
  const std::vector<char> defect_vertices =
      defect_faces.empty() ? std::vector<char>{} : vertex_flags(mesh, defect_faces);
  const Eigen::MatrixXd vd = as_column(defect_vertices), fd = as_column(defect_faces);
  switch (format) {
    case OutputFormat::none:
      return;
    case OutputFormat::vtp: {
      const Eigen::MatrixXd vt = v.vertex.col(result.column), ft = v.face.col(result.column);
      const Eigen::MatrixXd vhf = v.vertex.col(kColumnHf), fhf = v.face.col(kColumnHf);
      const Eigen::MatrixXd vhp = v.vertex.col(kColumnHp), fhp = v.face.col(kColumnHp);
      const Eigen::MatrixXd vfh = v.vertex.col(kColumnFh), ffh = v.face.col(kColumnFh);
      const Eigen::MatrixXd vn = v.vertex.middleCols(kColumnNf, 3);
      const Eigen::MatrixXd fn = v.face.middleCols(kColumnNf, 3);
      const Eigen::MatrixXd vw = v.vertex.col(kColumnWall), fw = v.face.col(kColumnWall);
      std::vector<output::MeshField> point_fields = {
          {"thickness", &vt}, {"h_f", &vhf}, {"h_p", &vhp}, {"f_h", &vfh}, {"n_f", &vn}};
      std::vector<output::MeshField> cell_fields = {
          {"thickness", &ft}, {"h_f", &fhf}, {"h_p", &fhp}, {"f_h", &ffh}, {"n_f", &fn}};
      if (result.column == kColumnWall) {
        point_fields.push_back({"wall", &vw});
        cell_fields.push_back({"wall", &fw});
      }
      if (!defect_faces.empty()) {
        point_fields.push_back({"defect", &vd});
        cell_fields.push_back({"defect", &fd});
      }
      output::write_vtp(path, mesh.vertices(), mesh.faces(), point_fields, cell_fields);
      return;
    }
    case OutputFormat::ply: {
      output::PlyColouring colouring;
      colouring.colour_minimum = result.statistics.minimum;
      colouring.colour_maximum = result.statistics.maximum;
      colouring.comment =
          "bemshape " + result.measure_column + " thickness, colours viridis from " +
          number_text(colouring.colour_minimum, 6) + " to " +
          number_text(colouring.colour_maximum, 6) + "; lengths in the input file's units" +
          (defect_faces.empty() ? ""
                                : "; magenta: within h0 of a region where the surface crosses "
                                  "itself, measured as given (property defect)");
      colouring.defect = defect_vertices;
      output::write_ply(path, mesh.vertices(), mesh.faces(), v.vertex.col(result.column),
                        colouring);
      return;
    }
    case OutputFormat::csv: {
      const bool wall = result.column == kColumnWall;
      const bool defect = !defect_faces.empty();
      Eigen::MatrixXd rows(mesh.num_vertices(), (wall ? 10 : 9) + (defect ? 1 : 0));
      rows.leftCols(3) = mesh.vertices();
      rows.col(3) = v.vertex.col(result.column);
      rows.col(4) = v.vertex.col(kColumnHf);
      rows.col(5) = v.vertex.col(kColumnHp);
      rows.middleCols(6, 3) = v.vertex.middleCols(kColumnNf, 3);
      std::vector<std::string> names = {"x", "y", "z", "thickness", "h_f", "h_p",
                                        "n_x", "n_y", "n_z"};
      if (wall) {
        rows.col(9) = v.vertex.col(kColumnWall);
        names.push_back("wall");
      }
      if (defect) {
        rows.col(rows.cols() - 1) = vd.col(0);
        names.push_back("defect");
      }
      output::write_csv(path, names, rows);
      return;
    }
  }
}

/// The parameters table of the HTML report.
std::vector<std::pair<std::string, std::string>> html_parameters(const ThicknessOptions& options,
                                                                 double h0,
                                                                 const ThicknessResult& result) {
  const analysis::BoundarySolve& run = result.boundary;
  return {{"input", options.input},
          {"h0", number_text(h0, 6) + " (" + result.h0_rule + ")"},
          {"a", number_text(options.a, 6)},
          {"measure", options.measure},
          {"edges", options.edges},
          {"min thickness",
           options.min_thickness ? number_text(*options.min_thickness, 6) : "none"},
          {"speck area", number_text(result.min_region_area, 6)},
          {"max edge", number_text(run.max_edge, 6) + " (" + run.max_edge_rule + ")"},
          {"solver faces", std::to_string(run.solver_mesh.num_faces())},
          {"input faces", std::to_string(result.input.report.faces)},
          {"solver", run.solution.report.method},
          {"bemshape", BEMSHAPE_VERSION}};
}

/// Regions listed in the printed report; the JSON report lists all of them.
constexpr std::size_t kPrintedRegions = 10;

/// Up to kPrintedRegions thin regions (or specks), one line each.
void print_thin_regions(std::ostream& out, const std::vector<ThinRegion>& regions) {
  for (std::size_t i = 0; i < std::min(regions.size(), kPrintedRegions); ++i) {
    const ThinRegion& r = regions[i];
    out << "    " << i + 1 << ". min " << number_text(r.minimum, 6) << " at "
        << point_text(r.min_location) << ", area " << number_text(r.area, 6) << ", centroid "
        << point_text(r.centroid) << '\n';
  }
  if (regions.size() > kPrintedRegions)
    out << "    ... " << regions.size() - kPrintedRegions << " more in the JSON report (--report)\n";
}

/// "N specks, total area A, thinnest M at (x, y, z)".
std::string specks_text(const analysis::ThinCheck& check) {
  const std::size_t n = check.specks.size();
  return std::to_string(n) + " speck" + (n == 1 ? "" : "s") + ", total area " +
         number_text(check.speck_total, 6) + ", thinnest " +
         number_text(check.specks.front().minimum, 6) + " at " +
         point_text(check.specks.front().min_location);
}

/// The check's lines of the printed report (docs/usage.md, "The check").
void print_check(std::ostream& out, double threshold, const ThicknessResult& result) {
  const analysis::ThinCheck& check = result.check;
  const std::string limit = number_text(threshold, 6);
  const std::string speck_area = number_text(check.speck_area, 6);
  if (check.pass) {
    out << "  check        PASS: no wall thinner than " << limit;
    if (!check.specks.empty())
      out << " over the speck area " << speck_area << "; set aside: " << specks_text(check);
    out << '\n';
    return;
  }
  if (!result.regions.empty()) {
    double area = 0.0;
    for (const ThinRegion& r : result.regions)
      area += r.area;
    out << "  check        FAIL: " << result.regions.size() << " region"
        << (result.regions.size() == 1 ? "" : "s") << " thinner than " << limit
        << ", total area " << number_text(area, 6) << '\n';
    print_thin_regions(out, result.regions);
    if (!check.specks.empty())
      out << "  specks       " << specks_text(check) << ", each under the speck area "
          << speck_area << " (in the JSON report)\n";
    return;
  }
  if (check.unmeasurable) {
    out << "  check        FAIL: no face has a measurable thickness at this h0, and the units "
           "check above says the lengths given do not fit the part's size\n";
    return;
  }
  out << "  check        FAIL: thinner than " << limit << " over area "
      << number_text(check.thin_area, 6) << ", at least the speck area " << speck_area
      << ", in " << check.specks.size() << " speck" << (check.specks.size() == 1 ? "" : "s")
      << " each smaller than it\n";
  print_thin_regions(out, check.specks);
}

void print_report(std::ostream& out, const ThicknessOptions& options, double h0,
                  const ThicknessResult& result, const StageTimes& times, double peak_mb,
                  const UnitsCheck& units) {
  const analysis::BoundarySolve& run = result.boundary;
  const ThicknessStatistics& s = result.statistics;
  const auto& sr = run.solution.report;
  out << "bemshape thickness: " << options.input << "  (lengths in the input file's units)\n";
  if (units.warning)
    out << "  warning      " << *units.warning << '\n';
  out
      << "  parameters   h0 " << number_text(h0, 6) << " (" << result.h0_rule << "), a "
      << number_text(options.a, 6) << ", measure " << options.measure << " ("
      << result.measure_column << "), edges " << options.edges << ", max edge "
      << number_text(run.max_edge, 6) << " (" << run.max_edge_rule << ")\n"
      << "  mesh         " << result.input.report.faces << " input faces, "
      << run.solver_mesh.num_faces() << " solver faces (longest edge "
      << number_text(run.solver_mesh.max_edge_length(), 6) << ")\n"
      << "  solver       " << sr.method << ", " << sr.unknowns << " unknowns, residual "
      << number_text(sr.residual, 6) << '\n';
  if (s.measured_area > 0.0)
    out << "  thickness    min " << number_text(s.minimum, 6) << " at " << point_text(s.min_location)
        << '\n'
        << "               p05 " << number_text(s.p05, 6) << ", median " << number_text(s.median, 6)
        << ", mean " << number_text(s.mean, 6) << ", p95 " << number_text(s.p95, 6) << ", max "
        << number_text(s.maximum, 6) << '\n';
  else
    out << "  thickness    not measurable on any face at this h0 (no opposite wall within its "
           "reach)\n";
  out << "  histogram    area per thickness range\n"
      << format_area_histogram(result.histogram, 30, "    ");
  if (s.unmeasurable_area > 0.0)
    out << "               not measurable (no opposite wall within reach of h0) on area "
        << number_text(s.unmeasurable_area, 6) << " of "
        << number_text(s.unmeasurable_area + s.measured_area, 6) << '\n';
  if (const Eigen::Index clamped = result.clamped_faces; clamped > 0)
    out << "  warning      thickness clamped to 0 on " << clamped << " solver face"
        << (clamped == 1 ? "" : "s") << ", where the inverse thickness exceeded 1/a:\n"
        << "               only discretisation error produces that. The solver mesh is probably\n"
        << "               too coarse for h0 there; try a smaller --max-edge, or an h0 nearer\n"
        << "               the walls' thickness\n";
  const std::vector<geometry::DefectZone>& defects = result.input.report.defects;
  if (!defects.empty()) {
    double marked = 0.0;
    std::size_t faces = 0;
    for (Eigen::Index f = 0; f < run.solver_mesh.num_faces(); ++f)
      if (result.defect_faces[static_cast<std::size_t>(f)] != 0) {
        marked += run.solver_mesh.face_areas()(f);
        ++faces;
      }
    out << "  warning      the surface crosses itself in " << defects.size() << " region"
        << (defects.size() == 1 ? "" : "s")
        << " that could not be repaired; measured on the surface as given there:\n";
    for (std::size_t i = 0; i < std::min(defects.size(), kPrintedRegions); ++i)
      out << "    " << i + 1 << ". " << number_text(defects[i].size(), 6) << " across around "
          << point_text(defects[i].centre()) << ": " << defects[i].why << '\n';
    if (defects.size() > kPrintedRegions)
      out << "    ... " << defects.size() - kPrintedRegions << " more in the JSON report (--report)\n";
    out << "               " << faces << " solver face" << (faces == 1 ? "" : "s")
        << " within h0 of them (area " << number_text(marked, 6) << " of "
        << number_text(run.solver_mesh.area(), 6)
        << ") are marked 'defect' in the outputs: the thickness there is not the part's\n";
  }
  if (result.column == analysis::kColumnWall) {
    const double total = run.solver_mesh.face_areas().sum();
    double unexpected = 0.0;
    out << "  fell back    area read from neighbours:";
    for (int k = 0; k < analysis::kFallbackKinds; ++k) {
      const analysis::FallbackFaces& b = result.wall.fallback[static_cast<std::size_t>(k)];
      out << (k ? ", " : " ") << analysis::to_string(static_cast<analysis::Fallback>(k)) << ' '
          << number_text(b.area, 6);
      if (static_cast<analysis::Fallback>(k) != analysis::Fallback::along_wall) unexpected += b.area;
    }
    out << " of " << number_text(total, 6) << '\n';
    if (unexpected > analysis::kFallbackWarningShare * total)
      out << "  warning      " << number_text(100.0 * unexpected / total, 3)
          << " % of the area has no wall reading of its own (no mid-surface, oblique, or near a\n"
          << "               rim without an opposite skin: walls drafted more than 18 degrees?);\n"
          << "               it took its neighbours' reading (the JSON report's \"fallback\" says\n"
          << "               where)\n";
  }
  if (options.min_thickness) {
    if (!defects.empty())
      out << "  check        (rests on the surface as given around the defect regions above)\n";
    print_check(out, *options.min_thickness, result);
  }
  if (options.max_thickness) {
    out << "  thick        " << result.thick_regions.size() << " region"
        << (result.thick_regions.size() == 1 ? "" : "s") << " thicker than "
        << number_text(*options.max_thickness, 6) << '\n';
    for (std::size_t i = 0; i < std::min(result.thick_regions.size(), kPrintedRegions); ++i) {
      const ThickRegion& r = result.thick_regions[i];
      out << "    " << i + 1 << ". max " << number_text(r.maximum, 6) << " at "
          << point_text(r.max_location);
      if (r.skeleton_point.allFinite())
        out << " (wall middle " << point_text(r.skeleton_point) << ")";
      out << ", area " << number_text(r.area, 6) << ", centroid " << point_text(r.centroid)
          << '\n';
    }
    if (result.thick_regions.size() > kPrintedRegions)
      out << "    ... " << result.thick_regions.size() - kPrintedRegions
          << " more in the JSON report (--report)\n";
  }
  out << "  timing      ";
  for (const auto& [stage, seconds] : times.stages())
    out << ' ' << stage << ' ' << seconds_text(seconds) << " s,";
  out << " total " << seconds_text(times.elapsed()) << " s\n"
      << "  memory       peak " << number_text(peak_mb, 6) << " MB, estimate "
      << number_text(double(result.boundary.solution.report.memory_estimate_bytes) / 1e6, 6)
      << " MB (the guard's bound, checked before the solve)\n";
  if (!options.output.empty())
    out << "  output       " << options.output << '\n';
  if (!options.solver_output.empty())
    out << "  solver mesh  " << options.solver_output << '\n';
}

void run_thickness(const ThicknessOptions& options, int& exit_code) {
  StageTimes times;
  const analysis::ThicknessMeasure measure = analysis::thickness_measure(options.measure);
  const analysis::EdgeMode edges = analysis::edge_mode(options.edges);
  // h0: --h0, else --min-thickness, else the part's 2·volume/area (analysis::part_h0).
  const bool h0_from_part = !options.h0 && !options.min_thickness;
  const double h0_given = options.h0 ? *options.h0 : options.min_thickness.value_or(1.0);
  if (options.h0 && !(std::isfinite(*options.h0) && *options.h0 > 0.0))
    throw InputError("--h0 must be a positive length (the smallest wall thickness of interest), "
                     "got " + number_text(*options.h0, 6));
  if (options.min_thickness &&
      !(std::isfinite(*options.min_thickness) && *options.min_thickness > 0.0))
    throw InputError("--min-thickness must be a positive length, got " +
                     number_text(*options.min_thickness, 6));
  const OutputFormat format = output_format(options.output);
  require_writable_folder(options.output, "-o");
  const OutputFormat solver_format = output_format(options.solver_output);
  require_writable_folder(options.solver_output, "--solver-output");
  require_writable_folder(options.report_path, "--report");
  require_writable_folder(options.html_path, "--html");
  if (options.threads < 0)
    throw InputError("--threads must be positive, got " + std::to_string(options.threads));
  if (options.units_check != "on" && options.units_check != "off")
    throw InputError("--units-check must be 'on' (warn when --h0 or --min-thickness cannot be "
                     "meant in the file's units) or 'off', got '" + options.units_check + "'");
  if (options.threads > 0)
    omp_set_num_threads(options.threads);

  ProgressDisplay display(options.quiet);
  analysis::ThicknessOptions job;
  job.solve = solve_options(h0_given, options.a, options.max_edge, options.sharp_angle,
                            options.solver, options.max_memory_bytes);
  job.solve.fit_memory = options.fit_memory;
  job.h0_from_part = h0_from_part;
  job.measure = measure;
  job.edges = edges;
  job.min_thickness = options.min_thickness;
  job.max_thickness = options.max_thickness;
  job.map_to_input = format != OutputFormat::none;
  job.min_region_area = options.min_region_area;
  // The units check needs only the part's box, area and volume, and the lengths given: it
  // runs on the prepared input before the solve, and its warning goes out at once.
  analysis::validate(job);
  const geometry::PreparedMesh input = times.time("read", [&] {
    return geometry::prepare_mesh_file(fs::path(options.input), {}, display.callback());
  });
  UnitsCheck units;
  units.enabled = options.units_check == "on";
  if (units.enabled) {
    std::vector<GivenLength> lengths;
    if (options.min_thickness)
      lengths.push_back({"--min-thickness", *options.min_thickness, true});
    if (options.h0)
      lengths.push_back({"--h0", *options.h0, false});
    units.warning = units_warning(part_size(input.mesh, input.report.volume, input.report.area),
                                  lengths, "--units-check off");
  }
  if (units.warning)
    std::cerr << "bemshape: warning: " << options.input << ": " << *units.warning << '\n';
  // A part in the wrong unit can read unmeasurable everywhere at h0: the check then fails
  // rather than the run refusing (docs/usage.md, "Units check").
  job.unmeasurable_fails_check = units.warning.has_value();
  const ThicknessResult result = analysis::measure_thickness(input, job, display.callback());
  const double h0 = result.h0;
  if (const std::string note = memory_fit_note(result.boundary); !note.empty())
    std::cerr << "bemshape: " << note << '\n';  // even with --quiet: the accuracy changed
  times.add(result.times);
  if (format != OutputFormat::none)
    times.time("write", [&] {
      report_progress(display.callback(), "write " + lower_extension(options.output), 0.0);
      write_output(options.output, format, result.input.mesh, result.input_features, result,
                   result.input.report.defects.empty()
                       ? std::vector<char>{}
                       : geometry::faces_near_defects(result.input.mesh,
                                                      result.input.report.defects, h0));
    });
  if (solver_format != OutputFormat::none)
    times.time("write", [&] {
      report_progress(display.callback(), "write solver mesh", 0.0);
      write_output(options.solver_output, solver_format, result.boundary.solver_mesh,
                   result.solver_features, result,
                   result.input.report.defects.empty() ? std::vector<char>{}
                                                       : result.defect_faces);
    });
  if (!options.html_path.empty())
    times.time("write", [&] {
      report_progress(display.callback(), "write HTML report", 0.0);
      ThicknessHtmlInput html{fs::path(options.input).filename().string(),
                              result.measure_column, &result.boundary.solver_mesh,
                              result.solver_features.vertex.col(result.column),
                              result.thickness, features::kMaxThicknessFactor * h0,
                              result.statistics, result.regions, result.check,
                              options.min_thickness, html_parameters(options, h0, result),
                              {}, {}, {}};
      html.defects = result.input.report.defects;
      html.defect_faces = result.defect_faces;
      if (units.warning)
        html.warnings.push_back(*units.warning);
      output::write_html_report(options.html_path, thickness_html_report(html));
    });
  display.finish();
  // Never a silent answer on a broken part: the defect regions also go to stderr, for runs
  // whose stdout nobody reads.
  if (const auto& defects = result.input.report.defects; !defects.empty())
    std::cerr << "bemshape: warning: " << options.input << ": the surface crosses itself in "
              << defects.size() << " region" << (defects.size() == 1 ? "" : "s")
              << " that could not be repaired (the largest " << number_text(defects[0].size(), 6)
              << " across around " << point_text(defects[0].centre())
              << "); measured on the surface as given there, the faces within h0 marked "
                 "'defect'\n";
  const double peak_mb = double(peak_resident_bytes()) / 1e6;
  if (!options.report_path.empty()) {
    const ThicknessRunNames names{
        options.input, options.measure,
        options.output.empty() ? std::nullopt : std::optional<std::string>(options.output),
        options.solver_output.empty() ? std::nullopt
                                      : std::optional<std::string>(options.solver_output)};
    output::write_file_atomically(
        options.report_path,
        thickness_report_json(job, result, names, times, {omp_get_max_threads(), peak_mb}, units)
                .dump(2) +
            '\n');
  }
  print_report(std::cout, options, h0, result, times, peak_mb, units);
  std::cout.flush();
  exit_code = options.min_thickness && !result.check.pass ? kExitCheckFailed : kExitSuccess;
}

}  // namespace

void register_thickness_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ThicknessOptions>();
  CLI::App* cmd = app.add_subcommand(
      "thickness",
      "Local wall thickness on the surface of a solid part (closed triangle mesh), with an "
      "optional minimum-wall-thickness check. Lengths are in the input file's units. Exit code "
      "0, 1 if --min-thickness finds thinner walls, 2 bad input, 3 numerical failure.");
  cmd->add_option("INPUT", options->input,
                  "Mesh file: .stl (ASCII or binary), .obj, .off, .ply, .3mf")
      ->required();
  cmd->add_option("--h0", options->h0,
                  "Characteristic length: about the smallest wall thickness of interest, in the "
                  "file's units (default: --min-thickness, else 2*volume/area of the part, the "
                  "wall of a plate)");
  cmd->add_option("--a", options->a, "Dimensionless diffusion parameter a of the PDE")
      ->capture_default_str();
  cmd->add_option("--measure", options->measure,
                  "wall: the thickness of the wall each point belongs to, read at the wall's "
                  "mid-surface; sphere (alias principal): h_p at the point, the inscribed "
                  "sphere's diameter there (larger near rims); paper: h_f, Yamada's f_h-based "
                  "thickness")
      ->capture_default_str();
  cmd->add_option("--edges", options->edges,
                  "wall: edges and corners read their walls' thickness; exact: also the "
                  "inscribed sphere at the point, so convex edges read thinner (measure wall)")
      ->capture_default_str();
  cmd->add_option("--min-thickness", options->min_thickness,
                  "Check: fail (exit 1) if the surface reads thinner than this over the speck "
                  "area or more (in all); lists the thin regions and the specks");
  cmd->add_option("--max-thickness", options->max_thickness,
                  "List the thick regions (hot spots for moulding and casting): walls thicker "
                  "than this, located at their thickest point and its wall's middle");
  cmd->add_option("--min-region-area", options->min_region_area,
                  "The speck area, in the file's units squared (default: h0^2/4; never more "
                  "than 0.1 % of the part's area): smaller thin regions are listed apart as "
                  "specks, smaller thick regions are dropped; the check fails when the thin "
                  "area in all reaches it");
  cmd->add_option("--units-check", options->units_check,
                  "on: warn in one line when --h0 or --min-thickness cannot be meant in the "
                  "file's units (larger than the part, or far from its walls); off: no warning")
      ->capture_default_str();
  add_solver_mesh_options(*cmd, options->max_edge, options->sharp_angle);
  add_solver_choice_options(*cmd, options->solver);
  cmd->add_option("-o,--output", options->output,
                  "Thickness on the input mesh: .vtp (ParaView), .ply (vertex colours), .csv");
  cmd->add_option("--solver-output", options->solver_output,
                  "Also write the thickness on the refined solver mesh (.vtp, .ply, .csv): the "
                  "values the statistics are computed from, before mapping to the input mesh");
  cmd->add_option("--report", options->report_path, "Also write the report as JSON to this file");
  cmd->add_option("--html", options->html_path,
                  "Also write a self-contained HTML page (one file, no network): the solver mesh "
                  "coloured by thickness, the thin regions, the histogram and the verdict");
  cmd->add_option("--threads", options->threads, "Number of threads (default: all cores)");
  cmd->add_flag("--quiet", options->quiet, "No progress on stderr");
  add_max_memory_option(*cmd, options->max_memory_bytes);
  cmd->add_flag("--fit-memory", options->fit_memory,
                "Where the solver mesh does not fit --max-memory (or the machine), solve on the "
                "coarser uniform mesh predicted to fit instead of refusing; the report says so "
                "(mesh.memory_fit)");
  add_timeout_option(*cmd);
  cmd->callback([options, &exit_code] { run_thickness(*options, exit_code); });
}

}  // namespace bemshape::apps
