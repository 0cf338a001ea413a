#pragma once

// What watches a flight that flies with the GIL released (thetad.run, thetad.compare): Ctrl-C and
// the caller's progress callback, both of which need the GIL, taken for them only.

#include <chrono>
#include <functional>
#include <string>

#include <pybind11/pybind11.h>

namespace thetad::python {

namespace py = pybind11;

class FlightObserver {
 public:
  // `progress`: None or a callable progress(t, duration) (simulated seconds). Built and destroyed
  // with the GIL held.
  explicit FlightObserver(py::object progress);

  // For Flight::fly's observe of the flight `label` of `duration` simulated seconds, called with
  // the GIL released. At most every kSignalPeriod of wall
  // time it takes the GIL and checks for signals: after a Ctrl-C it throws py::error_already_set
  // holding a KeyboardInterrupt that says where the flight stopped, which ends the flight (nothing
  // is returned, nothing written). It calls progress at most every kProgressPeriod; what progress
  // raises ends the flight the same way.
  std::function<void(double t)> hook(const std::string& label, double duration);

  // Once the flight `label` has ended at `end`, with the GIL held: raises the KeyboardInterrupt of
  // a Ctrl-C that came during it (a Python controller's code may have received it, and the run then
  // ended as failed), else calls progress(end, duration), so that a display reaches its end.
  void finished(const std::string& label, double end);

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kSignalPeriod{50};
  static constexpr std::chrono::milliseconds kProgressPeriod{100};

  void observe(const std::string& label, double t);
  // Throws py::error_already_set when a signal handler raised: a KeyboardInterrupt that says where
  // the flight `label` stopped, or whatever else the handler raised.
  void raise_pending_signal(const std::string& label, double t) const;

  py::object progress_;
  double duration_ = 0.0;
  Clock::time_point last_check_, last_report_;
};

}  // namespace thetad::python
