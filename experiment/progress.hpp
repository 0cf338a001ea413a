#pragma once

#include <chrono>
#include <functional>
#include <string>

namespace thetad {

// How far a flight has got, on stderr, with its rate and an ETA. On a terminal a person watches
// it is one line redrawn in place; anywhere else (CI set, a pipe, a cluster job's log) it is a
// plain line every `interval` (10 s; THETAD_PROGRESS_INTERVAL=SECONDS changes it), so a long run
// shows life without filling the log.
// A caller that is not a person at a terminal (the Python module) watches a task through an
// observer: called at every start and update and at the finish (done = total) of each task, it may
// throw to stop the work, which then ends by that exception (Ctrl-C in Python).
struct ProgressEvent {
  const std::string& label;
  double done, total;
  const std::string& unit;  // "" for simulated seconds
};
using ProgressObserver = std::function<void(const ProgressEvent&)>;

class Progress {
 public:
  enum class Mode { quiet, live, lines };
  // live when stderr is a terminal and CI is unset, lines otherwise; quiet when asked for.
  static Mode mode_for_stderr(bool quiet);

  explicit Progress(Mode mode, ProgressObserver observer = {});

  // One task of `total` units, shown under `label`: simulated seconds when `unit` is empty (with
  // the real-time factor), else counted things such as "evaluations".
  void start(const std::string& label, double total, const std::string& unit = {});
  // `note` follows the figures ("best 3.2e5").
  void update(double done, const std::string& note = {});
  // Ends the task's display with `outcome` ("completed (12.3 s wall)").
  void finish(const std::string& outcome);
  // A line of its own between tasks, saying what a step produced ("recorded 8500 samples ...").
  void note(const std::string& line);

  Mode mode() const { return mode_; }

 private:
  using Clock = std::chrono::steady_clock;
  std::string status(double done) const;
  std::string what() const;  // "12.5 s simulated", "40 evaluations"

  Mode mode_;
  ProgressObserver observer_;
  std::chrono::duration<double> interval_;
  std::string label_, unit_;
  double total_ = 0.0;
  Clock::time_point started_, last_shown_;
};

// The time between two plain lines: 10 s, or THETAD_PROGRESS_INTERVAL=SECONDS.
std::chrono::duration<double> progress_interval();

// "2 min 05 s", "43 s".
std::string format_duration(double seconds);

}  // namespace thetad
