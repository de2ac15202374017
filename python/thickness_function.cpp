// thickness(V, F, ...) → dict: the whole of `bemshape thickness` for arrays. The features are
// returned on the caller's own vertices and faces (carried over from the solver mesh by
// closest points, analysis/surface_features.hpp), so every array lines up with V and F
// whatever welding or repair the solver's copy needed; and on the solver mesh, where the
// statistics and regions are computed.
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "analysis/input_mesh.hpp"
#include "analysis/measure_thickness.hpp"
#include "apps/report/thickness_report_json.hpp"
#include "apps/report/units_check.hpp"
#include "apps/solver_choice.hpp"
#include "core/memory.hpp"
#include "core/number_text.hpp"
#include "python/json_to_python.hpp"
#include "python/module_functions.hpp"
#include "python/numpy_arrays.hpp"
#include "python/python_run.hpp"

namespace bemshape::python {
namespace {

using analysis::ThicknessMeasure;

/// The measure's name, as the command line's --measure takes it.
std::string measure_name(ThicknessMeasure measure) {
  switch (measure) {
    case ThicknessMeasure::wall:
      return "wall";
    case ThicknessMeasure::principal:
      return "principal";
    case ThicknessMeasure::paper:
      return "paper";
  }
  return "";
}

/// Bytes from max_memory (a positive number of bytes), 0 for None.
std::uint64_t memory_bytes(std::optional<double> bytes) {
  if (!bytes)
    return 0;
  if (!(std::isfinite(*bytes) && *bytes >= 1.0 && *bytes < 1.8e19))
    throw InputError("max_memory must be a positive number of bytes (e.g. 2e9), got " +
                     number_text(*bytes, 6));
  return static_cast<std::uint64_t>(*bytes);
}

/// The features of one mesh (rows of `values`) as views: thickness (the selected measure),
/// f_h, h_f, h_p (#rows) and n_f (#rows×3).
py::dict feature_views(const Eigen::MatrixXd& values, int column, const py::capsule& owner) {
  py::dict d;
  d["thickness"] = column_view(values, column, owner);
  d["f_h"] = column_view(values, analysis::kColumnFh, owner);
  d["h_f"] = column_view(values, analysis::kColumnHf, owner);
  d["h_p"] = column_view(values, analysis::kColumnHp, owner);
  d["n_f"] = columns_view(values, analysis::kColumnNf, 3, owner);
  d["wall"] = column_view(values, analysis::kColumnWall, owner);
  return d;
}

/// What the job hands back to Python; one capsule owns it and every array views into it.
struct Outcome {
  analysis::ThicknessResult result;
  analysis::SurfaceFeatures on_caller;  ///< on the caller's V and F
  nlohmann::json report;
};

py::dict thickness(const py::handle& V, const py::handle& F, std::optional<double> h0,
                   std::optional<double> min_thickness, std::optional<double> max_thickness,
                   std::optional<std::string> measure, double a, std::optional<double> max_edge,
                   std::optional<double> sharp_angle, const std::string& solver,
                   const std::string& far_field, std::optional<double> tolerance,
                   std::optional<int> threads,
                   std::optional<double> max_memory, bool fit_memory, py::object progress,
                   const std::string& name, std::optional<double> min_region_area,
                   bool units_check) {
  const Eigen::MatrixX3d vertices = positions_from_array(V, "V");
  const Eigen::MatrixX3i faces = indices_from_array(F, "F");
  analysis::ThicknessOptions job;
  // h0: h0, else min_thickness, else 2·volume/area of the part (analysis::part_h0).
  job.h0_from_part = !h0 && !min_thickness;
  job.solve = apps::solve_options(
      h0 ? *h0 : min_thickness.value_or(1.0), a, max_edge,
      sharp_angle,
      apps::SolverChoiceText{solver, tolerance, far_field}, memory_bytes(max_memory));
  job.solve.fit_memory = fit_memory;
  if (measure)
    job.measure = analysis::thickness_measure(*measure);
  job.min_thickness = min_thickness;
  job.max_thickness = max_thickness;
  job.min_region_area = min_region_area;
  job.map_to_input = false;  // mapped to the caller's own arrays below
  analysis::validate(job);
  const apps::ThicknessRunNames names{name, measure_name(job.measure), std::nullopt,
                                      std::nullopt};

  PythonRun run(threads, std::move(progress));
  auto [outcome, owner] = owned(run([&](const ProgressCallback& report_progress_to) {
    analysis::StageTimes times;
    const geometry::PreparedMesh input = times.time("prepare", [&] {
      return analysis::prepare_triangles(vertices, faces, name, report_progress_to);
    });
    apps::UnitsCheck units;
    units.enabled = units_check;
    if (units_check) {
      std::vector<apps::GivenLength> lengths;
      if (min_thickness)
        lengths.push_back({"min_thickness", *min_thickness, true});
      if (h0)
        lengths.push_back({"h0", *h0, false});
      const geometry::MeshReport& part = input.report;
      units.warning = apps::units_warning(
          apps::part_size(input.mesh, part.volume, part.area), lengths,
          "units_check=False");
    }
    // A part in the wrong unit can read unmeasurable everywhere at h0: the check then fails
    // rather than the call raising (docs/usage.md, "Units check").
    analysis::ThicknessOptions checked = job;
    checked.unmeasurable_fails_check = units.warning.has_value();
    Outcome o;
    o.result = analysis::measure_thickness(input, checked, report_progress_to);
    times.add(o.result.times);
    o.on_caller = times.time("map_back", [&] {
      report_progress(report_progress_to, "map to input mesh", 0.0);
      return analysis::transfer_features(o.result.boundary.solver_mesh, o.result.solver_features,
                                         geometry::SurfaceMesh(vertices, faces));
    });
    o.report = apps::thickness_report_json(
        checked, o.result, names, times, {run.threads(), double(peak_resident_bytes()) / 1e6},
        units);
    return o;
  }));

  const analysis::ThicknessResult& result = outcome->result;
  const geometry::SurfaceMesh& solver_mesh = result.boundary.solver_mesh;
  py::dict on_solver;
  on_solver["V"] = columns_view(solver_mesh.vertices(), 0, 3, owner);
  on_solver["F"] = indices_array(solver_mesh.faces());
  on_solver["vertex"] = feature_views(result.solver_features.vertex, result.column, owner);
  on_solver["face"] = feature_views(result.solver_features.face, result.column, owner);
  py::list regions;
  for (const analysis::ThinRegion& r : result.regions) {
    py::dict region;
    region["area"] = r.area;
    region["min"] = r.minimum;
    region["min_location"] = py::make_tuple(r.min_location.x(), r.min_location.y(), r.min_location.z());
    region["centroid"] = py::make_tuple(r.centroid.x(), r.centroid.y(), r.centroid.z());
    region["solver_faces"] = index_list(r.face_indices);
    regions.append(region);
  }
  py::dict out;
  out["vertex"] = feature_views(outcome->on_caller.vertex, result.column, owner);
  out["face"] = feature_views(outcome->on_caller.face, result.column, owner);
  out["measure"] = result.measure_column;
  const py::object report = to_python(outcome->report);
  out["statistics"] = report["thickness"];
  out["regions"] = regions;
  out["thick_regions"] = report["thick_regions"];
  out["passed"] = min_thickness ? py::object(py::bool_(result.check.pass)) : py::none();
  out["units_warning"] = report["units_warning"];
  out["solver_mesh"] = on_solver;
  out["report"] = report;
  return out;
}

}  // namespace

void register_thickness_function(py::module_& module) {
  const apps::SolverChoiceText solver;
  module.def(
      "thickness", &thickness, py::arg("V"), py::arg("F"), py::kw_only(),
      py::arg("h0") = py::none(), py::arg("min_thickness") = py::none(),
      py::arg("max_thickness") = py::none(), py::arg("measure") = py::none(),
      py::arg("a") = 0.2, py::arg("max_edge") = py::none(), py::arg("sharp_angle") = py::none(),
      py::arg("solver") = solver.method, py::arg("far_field") = solver.far_field,
      py::arg("tolerance") = py::none(), py::arg("threads") = py::none(),
      py::arg("max_memory") = py::none(), py::arg("fit_memory") = false,
      py::arg("progress") = py::none(), py::arg("name") = "numpy arrays",
      py::arg("min_region_area") = py::none(), py::arg("units_check") = true,
      R"(thickness(V, F, *, h0=None, min_thickness=None, max_thickness=None, measure=None,
          a=0.2, max_edge=None, sharp_angle=None, solver="auto", far_field="auto",
          tolerance=None, threads=None, max_memory=None, fit_memory=False, progress=None,
          name="numpy arrays", min_region_area=None, units_check=True) -> dict

The local wall thickness of the solid bounded by the triangles F (int (m, 3), 0-based) over
the vertices V (float (n, 3)), as `bemshape thickness` computes it for a file. Lengths in
the units of V.

h0: characteristic length, about the smallest wall of interest (default: min_thickness, else
    2·volume/area of the part).
min_thickness: the check's threshold: it fails when the faces thinner than it cover the speck
    area or more in all; every connected set of thinner faces is a region, and regions smaller
    than the speck area are set aside as specks (the report's check.specks).
min_region_area: the speck area (default h0²/4, never more than 0.1 % of the part's area).
units_check: warn (units_warning, and the report's) when h0 or min_thickness cannot be meant
    in the units of V (larger than the part, or far from its walls).
max_thickness: every connected set of thicker faces is a thick region (report's
    thick_regions).
measure: "wall" (the default: the thickness of the wall a point belongs to, read at the
    wall's mid-surface), "sphere"/"principal" (h_p at the point) or "paper" (h_f).
a, max_edge, sharp_angle, solver, far_field, tolerance: as the command line's --a, ...
threads: OpenMP threads for this call. max_memory: bytes the solve may use. fit_memory: where
    the solver mesh does not fit, solve on the coarser uniform mesh predicted to fit (the
    report's mesh["memory_fit"] says so) instead of raising ResourceError.
progress: callable(stage, fraction), called from the solve (with the GIL held).

Returns a dict:
  vertex, face: {thickness, f_h, h_f, h_p, wall: (n,) / (m,); n_f: (n, 3) / (m, 3)} on the
      caller's vertices and faces (views of memory the module owns, no copies);
  measure: "wall", "h_p" or "h_f";  thick_regions: as the report's (None without
      max_thickness);  statistics: area-weighted min, max, mean, median, p05, p95, ...;
  regions: thin regions, most severe first (area, min, min_location, centroid,
      solver_faces), specks aside;  passed: the check's verdict (None without
      min_thickness);  units_warning: one line, or None;
  solver_mesh: {V, F, vertex, face} the refined mesh the statistics come from;
  report: the JSON report of `bemshape thickness --report`, as a dict.
Raises ValueError for bad arrays or options and meshes that bound no solid, MemoryError
when the solve does not fit (max_memory), RuntimeError for a numerical failure,
KeyboardInterrupt on Ctrl-C (the solve stops within a second).)");
}

}  // namespace bemshape::python
