// thetad.Controller (C++ controllers and the base of Python ones), thetad.controller() and the
// registry's list.

#include <memory>
#include <optional>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "controllers/registry.hpp"
#include "core/helicopter/state.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/plant_registry.hpp"
#include "experiment/plugins.hpp"
#include "experiment/result_json.hpp"
#include "python/arrays.hpp"
#include "python/bindings.hpp"
#include "python/python_controller.hpp"
#include "python/values.hpp"

namespace thetad::python {

namespace {

Reference reference_of(py::handle value) {
  if (py::isinstance<Reference>(value)) return value.cast<Reference>();
  Reference reference;
  reference.position = VectorArgument(value, "compute: reference (a thetad.Reference or a position)", 3).vector();
  return reference;
}

// The spec `text` (NAME, LABEL=NAME, NAME:FILE, LABEL=NAME:FILE) with the settings given as keywords
// in place of a file's block.
ControllerSpec spec_with(const std::string& text, std::optional<std::string> label, const py::kwargs& settings) {
  ControllerSpec spec = parse_controller_spec(text);
  if (label) spec.label = *label;
  if (!settings.empty()) {
    if (!spec.settings_source.empty())
      throw py::value_error("controller '" + text + "': settings come from " + spec.settings_source +
                            " or from keywords, not both");
    spec.settings = to_yaml(settings, spec.controller);
  }
  check_label(spec.label);
  return spec;
}

// A registry's entries (controllers, plants): a dict per name, sorted by name.
template <class Factory>
py::list registered(const Registry<Factory>& registry) {
  py::list list;
  for (const std::string& name : registry.names()) {
    py::dict entry;
    entry["name"] = name;
    entry["description"] = registry.description(name);
    entry["origin"] = registry.origin(name);
    list.append(entry);
  }
  return list;
}

}  // namespace

void bind_controllers(py::module_& module) {
  py::class_<Reference>(module, "Reference",
                        "What a controller tracks at one sample: position (NED, m), its integral (m s), and the "
                        "commanded velocity (m/s) and acceleration (m/s²), the position's exact derivatives")
      .def(py::init([](py::handle position, py::handle integral, py::handle velocity, py::handle acceleration) {
             Reference reference;
             reference.position = VectorArgument(position, "Reference: position", 3).vector();
             if (!integral.is_none()) reference.integral = VectorArgument(integral, "Reference: integral", 3).vector();
             if (!velocity.is_none()) reference.velocity = VectorArgument(velocity, "Reference: velocity", 3).vector();
             if (!acceleration.is_none())
               reference.acceleration = VectorArgument(acceleration, "Reference: acceleration", 3).vector();
             return reference;
           }),
           py::arg("position"), py::arg("integral") = py::none(), py::arg("velocity") = py::none(),
           py::arg("acceleration") = py::none())
      .def_readwrite("position", &Reference::position)
      .def_readwrite("integral", &Reference::integral)
      .def_readwrite("velocity", &Reference::velocity)
      .def_readwrite("acceleration", &Reference::acceleration)
      .def("__repr__", [](const Reference& r) {
        return "Reference(position=" + py::repr(py::cast(r.position)).cast<std::string>() +
               ", velocity=" + py::repr(py::cast(r.velocity)).cast<std::string>() + ")";
      });

  py::class_<Controller, PythonController, std::shared_ptr<Controller>>(
      module, "Controller",
      "A controller thetad flies. Derive from it in Python and define compute(self, t, x, reference) -> u "
      "(x: the measured 18-state, u: the 5 inputs); reset(self, x0, t0) and name(self) are optional.")
      .def(py::init<>())
      .def("name", &Controller::name)
      .def(
          "reset",
          [](Controller& controller, py::handle x0, double t0) {
            controller.reset(VectorArgument(x0, "reset: x0", heli::kStateDim).vector(), t0);
          },
          py::arg("x0"), py::arg("t0") = 0.0)
      .def(
          "compute",
          [](Controller& controller, double t, py::handle x, py::handle reference) {
            const VectorArgument state(x, "compute: x", heli::kStateDim);
            Eigen::VectorXd u(heli::kInputDim);
            controller.control(t, state.vector(), reference_of(reference), u);
            return u;
          },
          py::arg("t"), py::arg("x"), py::arg("reference"),
          "u (5,) for the measured state x (18,) at time t; reference: a thetad.Reference or a position (3,)")
      .def("counters",
           [](const Controller& controller) {
             py::dict counters;
             for (const auto& [name, value] : controller.counters()) counters[py::str(name)] = value;
             return counters;
           })
      .def(
          "clone", [](const Controller& controller) { return std::shared_ptr<Controller>(controller.clone()); },
          "A copy: independent for a registered controller; for a Python class its own clone() when it defines "
          "one, else a second handle on the same object (docs/python.md)")
      .def("__repr__", [](py::handle self) {
        const std::string type = py::str(py::type::of(self).attr("__qualname__"));
        return "<" + type + " '" + self.cast<const Controller&>().name() + "'>";
      });

  py::class_<RegisteredController, Controller, std::shared_ptr<RegisteredController>>(
      module, "RegisteredController", "A registered controller built by thetad.controller()")
      .def_property_readonly("label", [](const RegisteredController& c) { return c.spec().label; })
      .def_property_readonly("controller", [](const RegisteredController& c) { return c.spec().controller; })
      .def_property_readonly("settings", [](const RegisteredController& c) { return to_python(yaml_to_json(c.settings())); },
                             "every setting as used, defaults included")
      .def("__repr__", [](const RegisteredController& c) {
        return "RegisteredController(label='" + c.spec().label + "', controller='" + c.spec().controller + "')";
      });

  module.def(
      "controller",
      [](const std::string& spec, std::optional<std::string> label, const std::string& scenario, const py::kwargs& settings) {
        const ControllerSpec parsed = spec_with(spec, label, settings);
        py::gil_scoped_release unlocked;
        auto flight = std::make_shared<const Flight>(scenario);
        auto built = std::make_shared<RegisteredController>(flight, flight->prepare(parsed));
        // Ready to compute(), as at the start of a run of the scenario.
        built->reset(flight->scenario().initial_state, 0.0);
        return built;
      },
      py::arg("spec"), py::kw_only(), py::arg("label") = py::none(), py::arg("scenario") = "scenario-1",
      "A registered controller by name with its settings as keywords, e.g. thetad.controller('theta-d', "
      "k=[...], l=[...]), designed for the scenario's model and initial state and reset to it. spec may also be "
      "'LABEL=NAME', 'NAME:SETTINGS.yaml' or 'LABEL=NAME:SETTINGS.yaml' (as on the command line).");

  module.def("controllers", [] { return registered(ControllerRegistry::instance()); },
             "The registered controllers: a dict per controller (name, description, origin)");
  module.def("plants", [] { return registered(PlantRegistry::instance()); },
             "The registered plants besides the helicopter (docs/plants.md): a dict per plant (name, description, "
             "origin)");

  module.def(
      "load_plugin", [](const std::string& library) { load_plugin(library); }, py::arg("library"),
      "Loads a plug-in (a shared library built with thetad_add_plugin, docs/api.md): its controllers and plants "
      "are then known to every function, as `thetad --plugin` makes them known to every command. Loading it "
      "again does nothing. The plug-ins THETAD_PLUGIN_PATH names are loaded when thetad is imported.");
  module.def(
      "_load_plugins_from_environment", [] {
        for (const auto& library : plugins_from_environment()) load_plugin(library);
      });
}

}  // namespace thetad::python
