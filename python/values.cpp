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

RunControls run_controls(const py::kwargs& keywords) {
  RunControls controls;
  const auto flag = [](py::handle value) { return value.cast<bool>(); };
  for (const auto& [key, value] : keywords) {
    const std::string name = key.cast<std::string>();
    if (name == "seed") controls.seed = value.cast<std::uint64_t>();
    else if (name == "duration") controls.duration = value.cast<double>();
    else if (name == "dt") controls.dt = value.cast<double>();
    else if (name == "log_every") controls.log_every = value.cast<int>();
    else if (name == "summary_only") controls.summary_only = flag(value);
    else if (name == "timing") controls.timing = flag(value);
    else if (name == "ideal") controls.ideal = flag(value);
    else if (name == "parameter_uncertainty") controls.parameter_uncertainty = flag(value);
    else if (name == "wind_gust") controls.wind_gust = flag(value);
    else if (name == "measurement_noise") controls.measurement_noise = flag(value);
    else if (name == "actuator_noise") controls.actuator_noise = flag(value);
    else if (name == "wind_noise") controls.wind_noise = flag(value);
    else if (name == "induced_velocity_noise") controls.induced_velocity_noise = flag(value);
    else if (name == "actuator_limits") controls.actuator_limits = flag(value);
    else if (name == "anti_windup") controls.anti_windup = flag(value);
    else
      throw py::type_error("unknown run control '" + name +
                           "' (seed, duration, dt, log_every, summary_only, timing, ideal, parameter_uncertainty, "
                           "wind_gust, measurement_noise, actuator_noise, wind_noise, induced_velocity_noise, actuator_limits, anti_windup)");
  }
  return controls;
}

}  // namespace thetad::python
