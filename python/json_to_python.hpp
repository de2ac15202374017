#pragma once
// A JSON report (apps/report/) as Python objects: objects → dict, arrays → list, numbers →
// int or float, strings → str, null → None. The module's reports are the command line's
// --report files, as dicts.

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

namespace bemshape::python {

pybind11::object to_python(const nlohmann::json& value);

}  // namespace bemshape::python
