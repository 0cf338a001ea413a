#pragma once

// What watches C++ work that runs with the GIL released (thetad.run, thetad.compare, thetad.tune):
// Ctrl-C and the caller's progress callback, both of which need the GIL, taken for them only.

#include <chrono>
#include <functional>
#include <string>

#include <pybind11/pybind11.h>

namespace thetad::python {

namespace py = pybind11;

// Ctrl-C for work that runs with the GIL released: Python runs its signal handlers only when the
// main thread holds the GIL and asks, so the work asks, at most every kSignalPeriod of wall time.
class SignalCheck {
 public:
  // With the GIL released: whether kSignalPeriod has passed since the last check (then take the
  // GIL and call raise_pending).
  bool due();
  // With the GIL held: throws py::error_already_set when a signal handler raised: a
  // KeyboardInterrupt saying `stopped()` (where the work stopped), or whatever else it raised.
  static void raise_pending(const std::function<std::string()>& stopped);

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kSignalPeriod{50};
  Clock::time_point last_ = Clock::now();
};

// `progress` when it is None or callable; a TypeError naming `signature` ("progress(t, duration)") otherwise.
py::object progress_callback(py::object progress, const std::string& signature);

class FlightObserver {
 public:
  // `progress`: None or a callable progress(t, duration) (simulated seconds). Built and destroyed
  // with the GIL held.
  explicit FlightObserver(py::object progress);

  // For Flight::fly's observe of the flight `label` of `duration` simulated seconds, called with
  // the GIL released. At each SignalCheck it takes the GIL and checks for signals: after a Ctrl-C
  // it throws py::error_already_set holding a KeyboardInterrupt that says where the flight stopped,
  // which ends the flight (nothing is returned, nothing written). It calls progress at most every
  // kProgressPeriod; what progress raises ends the flight the same way.
  std::function<void(double t)> hook(const std::string& label, double duration);

  // Once the flight `label` has ended at `end`, with the GIL held: raises the KeyboardInterrupt of
  // a Ctrl-C that came during it (a Python controller's code may have received it, and the run then
  // ended as failed), else calls progress(end, duration), so that a display reaches its end.
  void finished(const std::string& label, double end);

  // The shortest time between two calls of a progress callback, but for a task's first and last.
  static constexpr std::chrono::milliseconds kProgressPeriod{100};

 private:
  using Clock = std::chrono::steady_clock;

  void observe(const std::string& label, double t);
  // SignalCheck::raise_pending, saying where the flight `label` stopped.
  void raise_pending_signal(const std::string& label, double t) const;

  py::object progress_;
  double duration_ = 0.0;
  SignalCheck signals_;
  Clock::time_point last_report_ = Clock::now();
};

}  // namespace thetad::python
