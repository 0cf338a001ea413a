#pragma once

// The parts of the thetad module, one binding function per file, called by module.cpp in order
// (later parts use the classes earlier ones register).

#include <pybind11/pybind11.h>

namespace thetad::python {

void bind_numerics(pybind11::module_& module);     // numerics.cpp: care, lqr, lyap
void bind_model(pybind11::module_& module);        // model.cpp: Helicopter, trim, names
void bind_controllers(pybind11::module_& module);  // controllers.cpp: Controller, controller()
void bind_plants(pybind11::module_& module);       // plants.cpp: what thetad.Plant calls
void bind_flights(pybind11::module_& module);      // flights.cpp: run, compare, RunResult
void bind_bench(pybind11::module_& module);        // benchmark.cpp: bench
void bind_optimal(pybind11::module_& module);      // optimality.cpp: optimal, Optimality
void bind_campaigns(pybind11::module_& module);    // campaigns.cpp: campaign_run
void bind_figures(pybind11::module_& module);      // figures.cpp: _draw_figures, _shipped_script
void bind_tuning(pybind11::module_& module);       // tuning.cpp: tune

}  // namespace thetad::python
