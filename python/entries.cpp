#include "python/entries.hpp"

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "campaigns/factors.hpp"
#include "python/python_controller.hpp"

namespace thetad::python {

namespace {

// A campaign factor as a keyword (docs/campaigns.md): a number, or for a factor with names one of
// them (turbulence_intensity="severe"), read and checked as a campaign file's value.
void apply_factor(const Factor& factor, py::handle value, RunControls& controls) {
  try {
    factor.apply(factor_value(factor, py::str(value).cast<std::string>()), controls);
  } catch (const Error& error) {
    throw py::value_error(std::string(factor.name) + ": " + error.what());
  }
}

}  // namespace

RunControls run_controls(const py::kwargs& keywords) {
  RunControls controls;
  const auto flag = [](py::handle value) { return value.cast<bool>(); };
  // duration and dt are the earlier names of duration_s and dt_s (docs/glossary.md), kept working.
  for (const auto& [current, earlier] : {std::pair{"duration_s", "duration"}, std::pair{"dt_s", "dt"}}) {
    if (keywords.contains(current) && keywords.contains(earlier))
      throw py::type_error(std::string("give ") + current + " or its earlier name " + earlier + ", not both");
  }
  for (const auto& [key, value] : keywords) {
    const std::string name = key.cast<std::string>();
    if (name == "seed") controls.seed = value.cast<std::uint64_t>();
    else if (name == "duration_s" || name == "duration") controls.duration = value.cast<double>();
    else if (name == "dt_s" || name == "dt") controls.dt = value.cast<double>();
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
    else if (const Factor* factor = find_factor(name)) apply_factor(*factor, value, controls);
    else
      throw py::type_error("unknown run control '" + name +
                           "' (seed, log_every, summary_only, timing, ideal, parameter_uncertainty, wind_gust, "
                           "measurement_noise, actuator_noise, wind_noise, induced_velocity_noise, anti_windup, and "
                           "the campaign factors: " + factor_names() + ")");
  }
  return controls;
}

Entry entry_of(py::handle controller) {
  Entry entry;
  if (py::isinstance<py::str>(controller)) {
    entry.spec = parse_controller_spec(controller.cast<std::string>());
  } else if (py::isinstance<RegisteredController>(controller)) {
    entry.spec = controller.cast<const RegisteredController&>().spec();
  } else if (py::isinstance<Controller>(controller)) {
    auto borrowed = std::make_unique<BorrowedController>(py::reinterpret_borrow<py::object>(controller));
    const std::string type = py::str(py::type::of(controller).attr("__qualname__")).cast<std::string>();
    const std::string module = py::str(py::type::of(controller).attr("__module__")).cast<std::string>();
    ControllerSpec spec{borrowed->name(), "python:" + type, {}, {}};
    entry.python = PreparedController{spec, std::move(borrowed), {}, "python class " + module + "." + type};
  } else {
    throw py::type_error("controller: expected a registered controller's name (str), thetad.controller(...) or a "
                         "thetad.Controller subclass instance, got " +
                         py::str(py::type::of(controller).attr("__name__")).cast<std::string>());
  }
  return entry;
}

std::vector<Entry> entries_of(const py::sequence& controllers) {
  if (py::isinstance<py::str>(controllers))
    throw py::type_error("controllers: expected a list (['theta-d', 'sdre'] or ['all']), got the string '" +
                         controllers.cast<std::string>() + "'");
  std::vector<Entry> entries;
  std::vector<ControllerSpec> specs;
  const auto add = [&](py::handle controller) {
    entries.push_back(entry_of(controller));
    specs.push_back(spec_of(entries.back()));
  };
  for (const py::handle controller : controllers) {
    if (py::isinstance<py::str>(controller) && controller.cast<std::string>() == kAllControllers) {
      for (const auto& name : compared_controllers()) add(py::str(name));
    } else {
      add(controller);
    }
  }
  check_labels(specs);
  return entries;
}

ControllerSpec& spec_of(Entry& entry) { return entry.spec ? *entry.spec : entry.python->spec; }

PreparedController prepare(const Flight& flight, Entry& entry) {
  return entry.spec ? flight.prepare(*entry.spec) : std::move(*entry.python);
}

Flight flight_of(const std::optional<std::string>& scenario, const std::optional<std::string>& plant,
                 const std::optional<std::vector<double>>& initial_state, const RunControls& controls) {
  std::optional<Eigen::VectorXd> x0;
  if (initial_state)
    x0 = Eigen::Map<const Eigen::VectorXd>(initial_state->data(), static_cast<Eigen::Index>(initial_state->size()));
  return Flight::of_scenario_or_plant(scenario.value_or(""), plant.value_or(""), x0, controls);
}

}  // namespace thetad::python
