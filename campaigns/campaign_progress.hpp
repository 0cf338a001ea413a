#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "experiment/progress.hpp"

namespace thetad {

// A campaign's progress on stderr: runs done of the total, the rate, the ETA and the failures so
// far. Redrawn in place on a terminal; a plain line every progress_interval() (10 s) under CI, in
// a pipe or in a cluster job's log. An observer (experiment/progress.hpp) sees the runs done of the
// total as each is stored.
class CampaignProgress {
 public:
  // `total` runs of which `done` are already stored (resume).
  CampaignProgress(Progress::Mode mode, std::string name, std::int64_t total, std::int64_t done,
                   ProgressObserver observer = {});

  // Throws what the observer throws (the run is stored: a resume continues after it).
  void add(bool completed);
  // Shows the observer the count again, so that it can stop the campaign while no run ends.
  void tick() const { notify(); }
  void finish();

  std::int64_t flown() const { return flown_; }
  // Diverged or failed (docs/glossary.md, How a run ended).
  std::int64_t not_completed() const { return not_completed_; }

 private:
  using Clock = std::chrono::steady_clock;
  std::string status() const;
  void notify() const;

  Progress::Mode mode_;
  std::string name_;
  ProgressObserver observer_;
  std::int64_t total_, stored_, flown_ = 0, not_completed_ = 0;
  std::chrono::duration<double> interval_;
  Clock::time_point started_, last_shown_;
};

}  // namespace thetad
