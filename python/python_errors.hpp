#pragma once

// What Python code called from C++ (a controller's compute, a plant's f) raised, as the library
// reports it: one line for a thetad::Error's message, and a Ctrl-C kept for the front end.

#include <string>

#include <pybind11/pybind11.h>

namespace thetad::python {

namespace py = pybind11;

// "ZeroDivisionError: division by zero", without the traceback.
std::string describe(const py::error_already_set& error);

// A Ctrl-C that Python code called from a flight received (the signal is handled where Python runs)
// would end the run with a reason and be lost: it is raised again for the front end, which checks
// for signals once the flight has ended (TaskObserver::finished). Last, after every other call into
// Python: the interpreter may check for signals inside one and raise it there already.
void pass_on_interrupt(const py::error_already_set& error);

}  // namespace thetad::python
