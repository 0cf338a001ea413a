#include "python/flight_observer.hpp"

#include <cstdio>
#include <utility>

namespace thetad::python {

FlightObserver::FlightObserver(py::object progress)
    : progress_(std::move(progress)), last_check_(Clock::now()), last_report_(last_check_) {
  if (!progress_.is_none() && !PyCallable_Check(progress_.ptr()))
    throw py::type_error("progress: expected None or a callable progress(t, duration), got " +
                         py::str(py::type::of(progress_).attr("__name__")).cast<std::string>());
}

std::function<void(double)> FlightObserver::hook(const std::string& label, double duration) {
  duration_ = duration;
  return [this, label](double t) { observe(label, t); };
}

void FlightObserver::observe(const std::string& label, double t) {
  const Clock::time_point now = Clock::now();
  if (now - last_check_ < kSignalPeriod) return;
  last_check_ = now;
  py::gil_scoped_acquire locked;
  raise_pending_signal(label, t);
  if (!progress_.is_none() && now - last_report_ >= kProgressPeriod) {
    last_report_ = now;
    progress_(t, duration_);
  }
}

void FlightObserver::raise_pending_signal(const std::string& label, double t) const {
  if (PyErr_CheckSignals() == 0) return;
  if (PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) {
    char message[200];
    std::snprintf(message, sizeof message, "flight '%s' stopped at t = %.2f s of %.2f s simulated; no result",
                  label.c_str(), t, duration_);
    PyErr_Clear();
    PyErr_SetString(PyExc_KeyboardInterrupt, message);
  }
  throw py::error_already_set();
}

void FlightObserver::finished(const std::string& label, double end) {
  raise_pending_signal(label, end);
  if (!progress_.is_none()) progress_(end, duration_);
}

}  // namespace thetad::python
