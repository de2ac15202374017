// The compiled part of the Python package `bemshape`, its module bemshape._core (the
// package's __init__.py, python/bemshape/, names its functions bemshape.*): the library's
// jobs for numpy arrays (python/*_function.cpp, python/mesh_functions.cpp) and its error
// types as Python exceptions, each derived from the built-in one a Python user expects:
//   bemshape.InputError(ValueError)        bad arrays, options or meshes (exit code 2 in the CLI)
//   bemshape.ResourceError(MemoryError)    a solve that does not fit in max_memory or the machine
//   bemshape.NumericalError(RuntimeError)  no convergence, a singular system, a NaN
// Ctrl-C raises KeyboardInterrupt (python/python_run.hpp).
#include <pybind11/pybind11.h>

#include "core/errors.hpp"
#include "python/module_functions.hpp"

PYBIND11_MODULE(_core, module) {
  namespace py = pybind11;
  using namespace bemshape;
  module.doc() =
      "bemshape: local wall thickness, orientation and skeleton of solids given as closed "
      "triangle meshes, by the boundary element method (T. Yamada's shape-feature PDE).\n\n"
      "read_mesh(path) -> (V, F); check(V, F) -> dict; thickness(V, F, h0=...) -> dict; "
      "features(V, F, points, h0=...) -> dict. Lengths are in the units of V. See "
      "docs/usage.md, section 'Python'.";
  module.attr("__version__") = BEMSHAPE_VERSION;
  py::register_exception<InputError>(module, "InputError", PyExc_ValueError);
  py::register_exception<ResourceError>(module, "ResourceError", PyExc_MemoryError);
  py::register_exception<NumericalError>(module, "NumericalError", PyExc_RuntimeError);
  python::register_mesh_functions(module);
  python::register_thickness_function(module);
  python::register_features_function(module);
}
