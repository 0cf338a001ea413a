#pragma once

// What every flight-flying binding (run, compare, bench, optimal) takes from its caller: the run
// controls as keywords, the controllers as names, specs or Python objects, and the plant.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "experiment/controller_spec.hpp"
#include "experiment/flight.hpp"
#include "python/python_plant.hpp"
#include "settings/run_controls.hpp"

namespace thetad::python {

namespace py = pybind11;

// The run controls of docs/python.md, as keywords: the command line's --seed, --duration, ...
// TypeError for an unknown one.
RunControls run_controls(const py::kwargs& keywords);

// One controller of a run as the caller gave it: a spec (a name, or thetad.controller()'s, built
// again for the flight), or a Python controller flown as the object itself.
struct Entry {
  std::optional<ControllerSpec> spec;
  std::optional<PreparedController> python;
};

// A registered controller's name (str), thetad.controller(...) or a thetad.Controller subclass
// instance; TypeError for anything else.
Entry entry_of(py::handle controller);
// The entries of a sequence ("all": compared_controllers()), their labels checked to differ.
std::vector<Entry> entries_of(const py::sequence& controllers);

ControllerSpec& spec_of(Entry& entry);

// The plant= of a flight as the caller gave it: none, a registered plant's name, or a thetad.Plant
// instance, read (with the GIL) when this is made. TypeError for anything else.
struct PlantArgument {
  std::string name;                           // a registered plant's, or empty
  std::shared_ptr<const PythonPlant> python;  // or a plant written in Python
};
PlantArgument plant_argument(py::handle plant);

// The flight of `scenario` (a file or a shipped name; a file may name a plant) or of `plant` from
// `initial_state` (its own when none): Flight::of_scenario_or_plant, or Flight::of_plant for a plant
// written in Python. Needs no GIL.
Flight flight_of(const std::optional<std::string>& scenario, const PlantArgument& plant,
                 const std::optional<std::vector<double>>& initial_state, const RunControls& controls);

// The entry's controller for `flight`: built from its spec, or the Python object itself (moved out
// of the entry).
PreparedController prepare(const Flight& flight, Entry& entry);

}  // namespace thetad::python
