#include "python/values.hpp"

namespace thetad::python {

namespace py = pybind11;

YAML::Node to_yaml(py::handle value, const std::string& what) {
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
    return YAML::Node(py::repr(value).cast<std::string>());
  if (py::isinstance<py::str>(value)) return YAML::Node(value.cast<std::string>());
  if (py::isinstance<py::dict>(value)) {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& [key, item] : value.cast<py::dict>()) {
      const std::string name = py::str(key).cast<std::string>();
      map[name] = to_yaml(item, what + "." + name);
    }
    return map;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    YAML::Node sequence(YAML::NodeType::Sequence);
    for (const auto& item : value) sequence.push_back(to_yaml(item, what));
    return sequence;
  }
  // numpy arrays and scalars: as the Python values they hold.
  if (py::hasattr(value, "tolist") && py::hasattr(value, "dtype")) return to_yaml(value.attr("tolist")(), what);
  std::string message = what;
  message += ": expected numbers, bools, strings, lists or dicts, got ";
  message += py::str(py::type::of(value).attr("__name__")).cast<std::string>();
  throw py::type_error(message);
}

py::object to_python(const nlohmann::ordered_json& json) {
  return py::module_::import("json").attr("loads")(json.dump());
}

}  // namespace thetad::python
