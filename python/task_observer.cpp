#include "python/task_observer.hpp"

#include <cstdio>
#include <utility>

namespace thetad::python {

TaskObserver::TaskObserver(py::object progress)
    : progress_(std::move(progress)), last_check_(Clock::now()), last_report_(last_check_) {
  if (py::isinstance<py::bool_>(progress_)) {
    progress_ = progress_.cast<bool>() ? py::module_::import("thetad.progress").attr("progress_bar")() : py::none();
  }
  if (!progress_.is_none() && !PyCallable_Check(progress_.ptr()))
    throw py::type_error("progress: expected None, True (a bar) or a callable progress(done, total), got " +
                         py::str(py::type::of(progress_).attr("__name__")).cast<std::string>());
}

std::function<void(double)> TaskObserver::hook(const std::string& label, double duration) {
  total_ = duration;
  unit_.clear();
  return [this, label](double t) { observe(label, t, false); };
}

ProgressObserver TaskObserver::tasks() {
  return [this](const ProgressEvent& event) {
    total_ = event.total;
    unit_ = event.unit;
    // A task's start and end reach the display whatever the clock says, so that a bar opens and closes.
    observe(event.label, event.done, event.done == 0.0 || event.done == event.total);
  };
}

std::function<void(double)> TaskObserver::signals(const std::string& label) {
  return [this, label](double t) { observe(label, t, false, false); };
}

void TaskObserver::observe(const std::string& label, double done, bool last, bool report) {
  const Clock::time_point now = Clock::now();
  if (!last && now - last_check_ < kSignalPeriod) return;
  last_check_ = now;
  py::gil_scoped_acquire locked;
  raise_pending_signal(label, done);
  if (report && !progress_.is_none() && (last || now - last_report_ >= kProgressPeriod)) {
    last_report_ = now;
    progress_(done, total_);
  }
}

void TaskObserver::raise_pending_signal(const std::string& label, double done) const {
  if (PyErr_CheckSignals() == 0) return;
  if (PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) {
    char message[240];
    if (unit_.empty()) {
      std::snprintf(message, sizeof message, "flight '%s' stopped at t = %.2f s of %.2f s simulated; no result", label.c_str(),
                    done, total_);
    } else {
      std::snprintf(message, sizeof message, "'%s' stopped at %g of %g %s; no result", label.c_str(), done, total_,
                    unit_.c_str());
    }
    PyErr_Clear();
    PyErr_SetString(PyExc_KeyboardInterrupt, message);
  }
  throw py::error_already_set();
}

void TaskObserver::finished(const std::string& label, double end) {
  raise_pending_signal(label, end);
  if (!progress_.is_none()) progress_(end, total_);
}

}  // namespace thetad::python
