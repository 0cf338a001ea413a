#pragma once

// Python values to and from the library's YAML settings, JSON results and run controls.

#include <string>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>
#include <yaml-cpp/yaml.h>

#include "experiment/run_controls.hpp"

namespace thetad::python {

// A settings value (dict, list, tuple, numpy array, number, bool, str, None) as a YAML node, in
// the text a settings file would hold (floats by their shortest round-trip repr). TypeError
// naming `what` for anything else.
YAML::Node to_yaml(pybind11::handle value, const std::string& what);

// A JSON document as Python dicts, lists and numbers.
pybind11::object to_python(const nlohmann::ordered_json& json);

// The run controls of docs/python.md, given as keywords: the command line's --seed, --duration,
// ...; TypeError naming the known ones for any other keyword.
RunControls run_controls(const pybind11::kwargs& keywords);

}  // namespace thetad::python
