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

  // progress(end, duration) once a flight has ended at `end`, so that a display reaches its end.
  void finished(double end);

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kSignalPeriod{50};
  static constexpr std::chrono::milliseconds kProgressPeriod{100};

  void observe(const std::string& label, double t);

  py::object progress_;
  double duration_ = 0.0;
  Clock::time_point last_check_, last_report_;
};

}  // namespace thetad::python
