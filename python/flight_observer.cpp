#include "python/flight_observer.hpp"

#include <cstdio>
#include <utility>

namespace thetad::python {

bool SignalCheck::due() {
  const Clock::time_point now = Clock::now();
  if (now - last_ < kSignalPeriod) return false;
  last_ = now;
  return true;
}

void SignalCheck::raise_pending(const std::function<std::string()>& stopped) {
  if (PyErr_CheckSignals() == 0) return;
  if (PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) {
    PyErr_Clear();
    PyErr_SetString(PyExc_KeyboardInterrupt, stopped().c_str());
  }
  throw py::error_already_set();
}

py::object progress_callback(py::object progress, const std::string& signature) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw py::type_error("progress: expected None or a callable " + signature + ", got " +
                         py::str(py::type::of(progress).attr("__name__")).cast<std::string>());
  return progress;
}

FlightObserver::FlightObserver(py::object progress)
    : progress_(progress_callback(std::move(progress), "progress(t, duration)")) {}

std::function<void(double)> FlightObserver::hook(const std::string& label, double duration) {
  duration_ = duration;
  return [this, label](double t) { observe(label, t); };
}

void FlightObserver::observe(const std::string& label, double t) {
  if (!signals_.due()) return;
  const Clock::time_point now = Clock::now();
  py::gil_scoped_acquire locked;
  raise_pending_signal(label, t);
  if (!progress_.is_none() && now - last_report_ >= kProgressPeriod) {
    last_report_ = now;
    progress_(t, duration_);
  }
}

void FlightObserver::raise_pending_signal(const std::string& label, double t) const {
  SignalCheck::raise_pending([&] {
    char message[200];
    std::snprintf(message, sizeof message, "flight '%s' stopped at t = %.2f s of %.2f s simulated; no result",
                  label.c_str(), t, duration_);
    return std::string(message);
  });
}

void FlightObserver::finished(const std::string& label, double end) {
  raise_pending_signal(label, end);
  if (!progress_.is_none()) progress_(end, duration_);
}

}  // namespace thetad::python
