#pragma once
// The module's functions, one file per job: each registers its functions with their
// docstrings on the module (bemshape_module.cpp calls them).

#include <pybind11/pybind11.h>

namespace bemshape::python {

/// read_mesh(path) and check(V, F): mesh_functions.cpp.
void register_mesh_functions(pybind11::module_& module);

/// thickness(V, F, ...): thickness_function.cpp.
void register_thickness_function(pybind11::module_& module);

/// features(V, F, points, ...): features_function.cpp.
void register_features_function(pybind11::module_& module);

}  // namespace bemshape::python
