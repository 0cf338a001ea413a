// What thetad.Plant (python/thetad/plant.py) takes from C++: the SDC identity's check, through the
// same checked calls a flight makes (python/python_plant.hpp).

#include <algorithm>
#include <utility>

#include "python/arrays.hpp"
#include "python/bindings.hpp"
#include "python/python_plant.hpp"

namespace thetad::python {

void bind_plants(py::module_& module) {
  module.def(
      "_sdc_residual",
      [](py::object object, py::handle x, py::handle u) {
        const PythonPlant plant(std::move(object));
        const VectorArgument state(x, "sdc_residual: x", plant.state_dim());
        const Eigen::VectorXd input = u.is_none() ? plant.design_defaults().input
                                                  : Eigen::VectorXd(VectorArgument(u, "sdc_residual: u", plant.input_dim()).vector());
        const Eigen::VectorXd xdot = plant.f(state.vector(), input);
        const SdcPlant::Coefficients sdc = plant.sdc(state.vector(), input);
        return (sdc.F * state.vector() + sdc.B * input - xdot).lpNorm<Eigen::Infinity>() /
               std::max(1.0, xdot.lpNorm<Eigen::Infinity>());
      },
      py::arg("plant"), py::arg("x"), py::arg("u") = py::none());
}

}  // namespace thetad::python
