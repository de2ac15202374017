// features(V, F, points, ...) → dict of arrays: the whole of `bemshape features --points` for
// arrays: the shape features at points inside (and outside) the solid, by the boundary
// integral representation.
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "analysis/input_mesh.hpp"
#include "analysis/measure_features.hpp"
#include "apps/report/features_report_json.hpp"
#include "apps/solver_choice.hpp"
#include "core/memory.hpp"
#include "core/number_text.hpp"
#include "python/json_to_python.hpp"
#include "python/module_functions.hpp"
#include "python/numpy_arrays.hpp"
#include "python/python_run.hpp"

namespace bemshape::python {
namespace {

struct Outcome {
  analysis::FeaturesResult result;
  nlohmann::json report;
};

py::dict features(const py::handle& V, const py::handle& F, const py::handle& points, double h0,
                  double a, std::optional<double> skeleton_width, std::optional<double> max_edge,
                  std::optional<double> sharp_angle, const std::string& solver,
                  const std::string& far_field, std::optional<double> tolerance,
                  std::optional<int> threads,
                  std::optional<double> max_memory, py::object progress,
                  const std::string& name) {
  const Eigen::MatrixX3d vertices = positions_from_array(V, "V");
  const Eigen::MatrixX3i faces = indices_from_array(F, "F");
  const Eigen::MatrixX3d at = positions_from_array(points, "points");
  if (double(at.rows()) > analysis::kMaxPoints)
    throw ResourceError("points: " + std::to_string(at.rows()) + " points, more than the limit of " +
                        number_text(analysis::kMaxPoints, 4) + "; split them into smaller batches");
  if (max_memory && !(std::isfinite(*max_memory) && *max_memory >= 1.0 && *max_memory < 1.8e19))
    throw InputError("max_memory must be a positive number of bytes (e.g. 2e9), got " +
                     number_text(*max_memory, 6));
  analysis::FeaturesOptions job;
  job.solve = apps::solve_options(
      h0, a, max_edge, sharp_angle,
      apps::SolverChoiceText{solver, tolerance, far_field},
      max_memory ? static_cast<std::uint64_t>(*max_memory) : 0);
  job.skeleton_width = skeleton_width;
  analysis::validate(job);

  PythonRun run(threads, std::move(progress));
  auto [outcome, owner] = owned(run([&](const ProgressCallback& report_progress_to) {
    analysis::StageTimes times;
    const geometry::PreparedMesh input = times.time("prepare", [&] {
      return analysis::prepare_triangles(vertices, faces, name, report_progress_to);
    });
    Outcome o;
    o.result = analysis::measure_features(input, at, job, report_progress_to);
    times.add(o.result.times);
    o.report = apps::features_report_json(job, o.result, name, std::nullopt, times,
                                          {run.threads(), double(peak_resident_bytes()) / 1e6});
    return o;
  }));

  const analysis::FeaturesResult& r = outcome->result;
  const Eigen::Index np = r.points.rows();
  py::dict out;
  out["inside"] = flags_view(r.field.inside, owner);
  out["winding"] = column_view(r.field.winding, 0, owner);
  out["s"] = columns_view(r.field.s, 0, 3, owner);
  // ∂s_i/∂x_j at column 3i + j of the #P×9 column-major matrix: [p, i, j] at byte
  // 8·(p + (3i + j)·P).
  out["grad_s"] = py::array(py::dtype::of<double>(), {py::ssize_t(np), py::ssize_t(3), py::ssize_t(3)},
                            {py::ssize_t(sizeof(double)), py::ssize_t(3 * sizeof(double) * np),
                             py::ssize_t(sizeof(double) * np)},
                            r.field.gradient.data(), owner);
  out["f_h"] = column_view(r.features.f_h, 0, owner);
  out["h_f"] = column_view(r.features.h_f, 0, owner);
  out["h_p"] = column_view(r.features.h_p, 0, owner);
  out["eigenvalues"] = columns_view(r.features.eigenvalues, 0, 3, owner);
  out["n_f"] = columns_view(r.features.n_f, 0, 3, owner);
  out["t_f"] = columns_view(r.features.t_f, 0, 3, owner);
  out["across"] = columns_view(r.features.across, 0, 3, owner);
  out["skeleton"] = flags_view(r.features.skeleton, owner);
  out["report"] = to_python(outcome->report);
  return out;
}

}  // namespace

void register_features_function(py::module_& module) {
  const apps::SolverChoiceText solver;
  module.def(
      "features", &features, py::arg("V"), py::arg("F"), py::arg("points"), py::kw_only(),
      py::arg("h0"), py::arg("a") = 0.2, py::arg("skeleton_width") = py::none(),
      py::arg("max_edge") = py::none(), py::arg("sharp_angle") = py::none(),
      py::arg("solver") = solver.method, py::arg("far_field") = solver.far_field,
      py::arg("tolerance") = py::none(), py::arg("threads") = py::none(),
      py::arg("max_memory") = py::none(), py::arg("progress") = py::none(),
      py::arg("name") = "numpy arrays",
      R"(features(V, F, points, *, h0, a=0.2, skeleton_width=None, max_edge=None,
         sharp_angle=None, solver="auto", far_field="auto", tolerance=None, threads=None,
         max_memory=None, progress=None, name="numpy arrays") -> dict

The shape features at `points` (float (P, 3)) of the solid bounded by F over V, as
`bemshape features --points` computes them: no volume mesh. Lengths in the units of V; h0
is required (about the smallest wall of interest); the other options as for thickness().

Returns a dict of arrays (views of memory the module owns, no copies), P rows each:
  inside (bool), winding (float: 1 inside, 0 outside), s (P, 3), grad_s (P, 3, 3) with
  grad_s[p, i, j] = ds_i/dx_j, f_h, h_f, h_p (P,), eigenvalues (P, 3, ascending),
  n_f, t_f, across (P, 3), skeleton (bool); and report: the JSON report of
  `bemshape features --report`, as a dict. Outside points have f_h = h_f = h_p = 0.
Raises as thickness() does; MemoryError for more than 10^6 points.)");
}

}  // namespace bemshape::python
