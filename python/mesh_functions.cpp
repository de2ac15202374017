// read_mesh(path) → (V, F) and check(V, F) → dict: a mesh file's triangles as arrays, and the
// validation and repair report of `bemshape check` for arrays.
#include <filesystem>

#include <pybind11/stl/filesystem.h>

#include "analysis/input_mesh.hpp"
#include "apps/report/mesh_report_json.hpp"
#include "geometry/mesh_io.hpp"
#include "python/json_to_python.hpp"
#include "python/module_functions.hpp"
#include "python/numpy_arrays.hpp"
#include "python/python_run.hpp"

namespace bemshape::python {
namespace {

py::tuple read_mesh(const std::filesystem::path& path) {
  PythonRun run(std::nullopt, py::none());
  geometry::TriangleSoup soup = run([&](const ProgressCallback&) {
    return geometry::read_triangle_soup(path);
  });
  const auto [vertices, owner] = owned(std::move(soup.vertices));
  return py::make_tuple(columns_view(*vertices, 0, 3, owner), indices_array(soup.faces));
}

py::object check(const py::handle& V, const py::handle& F, const std::string& name) {
  const Eigen::MatrixX3d vertices = positions_from_array(V, "V");
  const Eigen::MatrixX3i faces = indices_from_array(F, "F");
  PythonRun run(std::nullopt, py::none());
  const nlohmann::json report = run([&](const ProgressCallback& progress) {
    return apps::mesh_report_json(analysis::inspect_triangles(vertices, faces, name, progress).report);
  });
  return to_python(report);
}

}  // namespace

void register_mesh_functions(py::module_& module) {
  module.def("read_mesh", &read_mesh, py::arg("path"),
             R"(read_mesh(path) -> (V, F)

The triangles of a mesh file (.stl ASCII or binary, .obj, .off, .ply, .3mf) as stored in it:
V, float64 array (n, 3) of vertex positions in the file's units (3MF: every build item with
its transforms, in the unit the file records, not converted); F, int64 array (m, 3) of
0-based vertex indices (polygons split into triangle fans). Nothing is welded or repaired
here: thickness(), features() and check() do that. Raises ValueError (bemshape.InputError)
for a file that cannot be read, naming the file and the problem.)");
  module.def("check", &check, py::arg("V"), py::arg("F"), py::kw_only(),
             py::arg("name") = "numpy arrays",
             R"(check(V, F, *, name="numpy arrays") -> dict

Validates the triangles F (int (m, 3), 0-based) over the vertices V (float (n, 3)) as the
boundary of a solid and repairs what is safely repairable, exactly as `bemshape check` does
for a file: the dict is its JSON report (faces, vertices, shells, cavities, volume, area,
bounding_box, problems with status/what/count/first_at/consequence, repairs, usable). A mesh
that cannot be used gives usable=False (no exception); arrays of the wrong shape or type,
indices out of range and non-finite positions raise ValueError. `name` stands for the mesh
in the report and in messages.)");
}

}  // namespace bemshape::python
