#include <pybind11/pybind11.h>

#include "core/error.hpp"
#include "experiment/build_info.hpp"
#include "python/bindings.hpp"

PYBIND11_MODULE(_thetad, module) {
  module.doc() = "thetad: θ–D, SDRE and LQR controllers on a nonlinear miniature helicopter (docs/python.md)";
  // Every precondition and numerical failure of the library, with its message.
  pybind11::register_exception<thetad::Error>(module, "Error", PyExc_RuntimeError);
  module.attr("__version__") = thetad::build_info().version;
  thetad::python::bind_numerics(module);
  thetad::python::bind_model(module);
  thetad::python::bind_controllers(module);
  thetad::python::bind_plants(module);
  thetad::python::bind_flights(module);
  thetad::python::bind_bench(module);
  thetad::python::bind_optimal(module);
  thetad::python::bind_campaigns(module);
  thetad::python::bind_figures(module);
  thetad::python::bind_tuning(module);
}
