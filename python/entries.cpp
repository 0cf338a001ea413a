#include "python/entries.hpp"

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "campaigns/factors.hpp"
#include "core/error.hpp"
#include "settings/run_settings.hpp"
#include "python/python_controller.hpp"

namespace thetad::python {

namespace {

// A keyword's value as the setting's command-line option reads it (a switch as a bool), or without
// an option as a campaign value (docs/campaigns.md): a number, or for a choice one of its names
// (turbulence_intensity="severe"), checked against the setting's range.
void apply_keyword(const RunSetting& setting, py::handle value, RunControls& controls) {
  if (setting.value == RunSetting::Value::on_off) {
    setting.apply(value.cast<bool>() ? 1.0 : 0.0, controls);
  } else if (setting.parse) {
    setting.parse(py::str(value).cast<std::string>(), controls);
  } else if (setting.option_form == RunSetting::Option::value) {
    setting.apply(setting.value == RunSetting::Value::whole ? value.cast<int>() : value.cast<double>(), controls);
  } else {
    try {
      setting.apply(factor_value(setting, py::str(value).cast<std::string>()), controls);
    } catch (const Error& error) {
      throw py::value_error(std::string(setting.name) + ": " + error.what());
    }
  }
}

}  // namespace

RunControls run_controls(const py::kwargs& keywords) {
  RunControls controls;
  // duration and dt are the earlier names of duration_s and dt_s (docs/glossary.md), kept working.
  for (const auto& [current, earlier] : {std::pair{"duration_s", "duration"}, std::pair{"dt_s", "dt"}}) {
    if (keywords.contains(current) && keywords.contains(earlier))
      throw py::type_error(std::string("give ") + current + " or its earlier name " + earlier + ", not both");
  }
  for (const auto& [key, value] : keywords) {
    const std::string name = key.cast<std::string>();
    const RunSetting* setting = find_run_setting(name);
    if (setting == nullptr || setting->value == RunSetting::Value::none) {
      std::string known;
      for (const RunSetting& each : run_settings()) {
        if (each.value != RunSetting::Value::none) known += (known.empty() ? "" : ", ") + std::string(each.name);
      }
      throw py::type_error("unknown run control '" + name + "' (" + known + ")");
    }
    apply_keyword(*setting, value, controls);
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

PlantArgument plant_argument(py::handle plant) {
  if (plant.is_none()) return {};
  if (py::isinstance<py::str>(plant)) return {plant.cast<std::string>(), nullptr};
  if (py::isinstance(plant, py::module_::import("thetad.plant").attr("Plant")))
    return {{}, std::make_shared<const PythonPlant>(py::reinterpret_borrow<py::object>(plant))};
  throw py::type_error("plant: expected a registered plant's name (str, thetad.plants()) or a thetad.Plant subclass "
                       "instance, got " +
                       py::str(py::type::of(plant).attr("__name__")).cast<std::string>());
}

Flight flight_of(const std::optional<std::string>& scenario, const PlantArgument& plant,
                 const std::optional<std::vector<double>>& initial_state, const RunControls& controls) {
  std::optional<Eigen::VectorXd> x0;
  if (initial_state)
    x0 = Eigen::Map<const Eigen::VectorXd>(initial_state->data(), static_cast<Eigen::Index>(initial_state->size()));
  if (!plant.python) return Flight::of_scenario_or_plant(scenario.value_or(""), plant.name, x0, controls);
  if (scenario) throw Error("a flight needs a scenario or a plant, not both");
  if (!x0 && !plant.python->initial_state())
    throw Error("plant " + plant.python->name() + ": give initial_state (the class has no initial_state of its own)");
  return Flight::of_plant(plant.python, plant.python->name(), x0 ? *x0 : *plant.python->initial_state(), controls);
}

}  // namespace thetad::python
