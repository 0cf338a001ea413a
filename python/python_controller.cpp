#include "python/python_controller.hpp"

#include <pybind11/numpy.h>

#include "core/error.hpp"
#include "python/arrays.hpp"
#include "python/python_errors.hpp"

namespace thetad::python {

std::string PythonController::class_name() const {
  py::gil_scoped_acquire gil;
  return py::str(py::type::of(py::cast(static_cast<const Controller*>(this))).attr("__qualname__")).cast<std::string>();
}

std::string PythonController::name() const {
  py::gil_scoped_acquire gil;
  if (const py::function override = py::get_override(static_cast<const Controller*>(this), "name"))
    return py::str(override()).cast<std::string>();
  return class_name();
}

void PythonController::reset(const Eigen::VectorXd& x0, double t0) {
  py::gil_scoped_acquire gil;
  try {
    if (const py::function override = py::get_override(static_cast<const Controller*>(this), "reset"))
      override(py::array(x0.size(), x0.data()), t0);
  } catch (const py::error_already_set& error) {
    Error failure(class_name() + ".reset raised " + describe(error));
    pass_on_interrupt(error);
    throw failure;
  }
}

void PythonController::control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                               const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  py::gil_scoped_acquire gil;
  try {  // the look-up too: a Ctrl-C can be raised there
    const py::function compute = py::get_override(static_cast<const Controller*>(this), "compute");
    if (!compute) throw Error(class_name() + " does not define compute(self, t, x, reference)");
    const py::object result = compute(t, py::array(measured_state.size(), measured_state.data()), reference);
    u = VectorArgument(result, class_name() + ".compute returned u", u.size()).vector();
  } catch (const py::error_already_set& error) {
    Error failure(class_name() + ".compute raised " + describe(error));
    pass_on_interrupt(error);
    throw failure;
  } catch (const py::builtin_exception& error) {  // what VectorArgument raises for a wrong u
    throw Error(error.what());
  }
}

std::unique_ptr<Controller> PythonController::clone() const {
  py::gil_scoped_acquire gil;
  const py::object self = py::cast(static_cast<const Controller*>(this));
  try {
    if (const py::function override = py::get_override(static_cast<const Controller*>(this), "clone")) {
      py::object copy = override();
      if (!py::isinstance<Controller>(copy))
        throw Error(class_name() + ".clone must return a thetad.Controller");
      return std::make_unique<BorrowedController>(std::move(copy));
    }
  } catch (const py::error_already_set& error) {
    throw Error(class_name() + ".clone raised " + describe(error));
  }
  return std::make_unique<BorrowedController>(self);
}

BorrowedController::BorrowedController(py::object object)
    : object_(std::move(object)), target_(object_.cast<Controller*>()) {}

BorrowedController::~BorrowedController() {
  // The last C++ reference may go on a thread that does not hold the GIL.
  py::gil_scoped_acquire gil;
  object_ = py::object();
}

RegisteredController::RegisteredController(std::shared_ptr<const Flight> flight, PreparedController prepared)
    : flight_(std::move(flight)), prepared_(std::move(prepared)) {}

std::unique_ptr<Controller> RegisteredController::clone() const {
  return std::make_unique<RegisteredController>(
      flight_, PreparedController{prepared_.spec, prepared_.controller->clone(), prepared_.settings, prepared_.origin});
}

}  // namespace thetad::python
