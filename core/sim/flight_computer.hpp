#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace thetad::sim {

// The flight computer in the loop (docs/model.md §15.7): a computation started at a controller
// sample reaches the servos after its latency, and while it runs the computer starts no other.
// Off (latency none, the default): every input reaches the servos at its own sample, as before.
struct FlightComputerSettings {
  enum class Latency {
    none,       // no latency: the input of sample k acts from t_k
    fixed,      // every computation takes `fixed` seconds
    measured,   // `slowdown` times the control() call's wall time on this host (not reproducible)
    step_time,  // `slowdown` times the controller's `step_time` (from a bench file's `step_times`)
  };
  static constexpr std::array<const char*, 4> kLatencyNames = {"none", "fixed", "measured", "step-time"};
  // When a computation overruns the period (Cervin 2005's names): skip_next lets it finish, applies
  // its input when it is ready and starts the next computation at the first sample after that,
  // from the newest measurement (the samples in between start none); abort stops it at the next
  // sample, keeps the input that was acting, and starts the next computation on time.
  enum class Overrun { skip_next, abort };
  static constexpr std::array<const char*, 2> kOverrunNames = {"skip-next", "abort"};

  Latency latency = Latency::none;
  double fixed = 0.0;     // s
  double slowdown = 1.0;  // measured, step_time: the flight computer is this many times slower
  Overrun overrun = Overrun::skip_next;
  // step_time: each controller's step time (s) by its label, what measured them (the bench file's
  // name, its SHA-256 and the statistic taken, for the result's provenance), and the step time of
  // the controller this run flies, which the front end takes from step_times by its label.
  std::vector<std::pair<std::string, double>> step_times;
  std::string step_time_source;
  double step_time = 0.0;

  bool active() const { return latency != Latency::none; }
  // Throws thetad::Error naming the first setting out of range.
  void validate() const;
  // The step time given for the controller labelled `label`; throws thetad::Error naming it and
  // the labels there are when there is none.
  double step_time_of(const std::string& label) const;

  // A latency beyond a minute, or a computer a million times slower, is a mistake, not a study.
  static constexpr double kMaxLatency = 60.0;
  static constexpr double kMaxSlowdown = 1e6;
};

// What the flight computer did in one run (RunSummary::computer).
struct ComputerCounts {
  std::int64_t computations = 0;     // control() calls
  std::int64_t missed_deadlines = 0;  // computations whose latency exceeded the period
  std::int64_t longest_missed_run = 0; // the most consecutive computations that missed
  std::int64_t skipped_samples = 0;  // samples that started no computation: the computer was busy
  std::int64_t aborted = 0;          // computations stopped at their deadline (Overrun::abort)
  double max_latency = 0.0;          // s
  double mean_latency = 0.0;         // s, over the computations
};

// The schedule of one run's computations, sample by sample: whether the computer is free at a
// sample, and in which period, and where in it, the pending result reaches the servos. Times are
// offsets from the run's start; sample k is at k T. Allocates nothing.
//
// The first computation (sample 0) counts as done before the flight: its input acts from t0, and
// the computer is free at sample 1.
class FlightComputer {
 public:
  FlightComputer(const FlightComputerSettings& settings, double period);

  // Whether a computation starts at sample k.
  bool free_at(std::int64_t k) const;
  // A computation started at sample k whose control() call took `wall_ns` on this host (0 when
  // not measured); returns its latency (s).
  double start(std::int64_t k, std::int64_t wall_ns);
  // Sample k started no computation.
  void skip() { ++counts_.skipped_samples; }
  // Where in sample k's period [t_k, t_k + T) the pending result reaches the servos (an offset in
  // [0, T)), or nothing when none does; the result is then no longer pending.
  std::optional<double> arrival(std::int64_t k);

  // The counts so far, the mean latency included.
  ComputerCounts counts() const;

 private:
  FlightComputerSettings::Latency latency_;
  FlightComputerSettings::Overrun overrun_;
  double fixed_, slowdown_, step_time_, period_;
  double busy_until_ = 0.0;   // s
  double ready_at_ = 0.0;     // s: when the pending result reaches the servos
  bool pending_ = false;
  std::int64_t missed_run_ = 0;
  double latency_sum_ = 0.0;
  ComputerCounts counts_;
};

}  // namespace thetad::sim
