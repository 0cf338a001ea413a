#pragma once

// What watches work that runs with the GIL released (a flight, a benchmark, a solve, a campaign):
// Ctrl-C and the caller's progress callback, both of which need the GIL, taken for them only.

#include <chrono>
#include <functional>
#include <string>

#include <pybind11/pybind11.h>

#include "experiment/progress.hpp"

namespace thetad::python {

namespace py = pybind11;

class TaskObserver {
 public:
  // `progress`: None, a callable progress(done, total) (simulated seconds of a flight, or the
  // task's units), or True: thetad.progress.progress_bar(), a tqdm bar when tqdm is installed.
  // Built and destroyed with the GIL held.
  explicit TaskObserver(py::object progress);

  // For Flight::fly's observe of the flight `label` of `duration` simulated seconds, called with
  // the GIL released.
  std::function<void(double t)> hook(const std::string& label, double duration);
  // For a library task's Progress (experiment/progress.hpp), called with the GIL released: each of
  // its tasks reports progress(done, total) anew.
  ProgressObserver tasks();
  // For work that reports no progress of its own (a tuning search's draws, flown on its threads):
  // Ctrl-C only, saying it stopped `label`.
  std::function<void(double t)> signals(const std::string& label);

  // Both observe at most every kSignalPeriod of wall time: they take the GIL and check for
  // signals; after a Ctrl-C they throw py::error_already_set holding a KeyboardInterrupt that says
  // where the work stopped, which ends it (nothing is returned, nothing written). They call
  // progress at most every kProgressPeriod; what progress raises ends the work the same way.

  // Once the work `label` has ended at `end`, with the GIL held: raises the KeyboardInterrupt of a
  // Ctrl-C that came during it (a Python controller's code may have received it, and the run then
  // ended as failed), else calls progress(end, total), so that a display reaches its end.
  void finished(const std::string& label, double end);

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kSignalPeriod{50};
  static constexpr std::chrono::milliseconds kProgressPeriod{100};

  // Checks for signals (always when `last`, else at most every kSignalPeriod) and, when `report`,
  // calls progress.
  void observe(const std::string& label, double done, bool last, bool report = true);
  // Throws py::error_already_set when a signal handler raised: a KeyboardInterrupt that says where
  // the work `label` stopped, or whatever else the handler raised.
  void raise_pending_signal(const std::string& label, double done) const;

  py::object progress_;
  double total_ = 0.0;
  std::string unit_;  // "" for a flight's simulated seconds
  Clock::time_point last_check_, last_report_;
};

}  // namespace thetad::python
