#include "python/python_errors.hpp"

namespace thetad::python {

std::string describe(const py::error_already_set& error) {
  std::string text = py::str(error.type().attr("__name__")).cast<std::string>();
  text += ": ";
  text += py::str(error.value()).cast<std::string>();
  return text;
}

void pass_on_interrupt(const py::error_already_set& error) {
  if (error.matches(PyExc_KeyboardInterrupt)) PyErr_SetInterrupt();
}

}  // namespace thetad::python
