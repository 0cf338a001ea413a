#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "core/control_law.hpp"
#include "experiment/flight.hpp"

namespace thetad {

// Per-step cost of controllers outside the simulation loop (`thetad bench`): the control() calls
// of each controller on the same states, recorded along a flight of the scenario, timed one by one
// on one pinned core, after a warm-up, repetitions interleaved across the controllers so that a
// slow phase of a noisy host hits them all alike.

// What control() received at every sample of a flight (time, measured state, reference): the
// states a controller is timed on.
struct RecordedSamples {
  std::vector<double> time;
  std::vector<Eigen::VectorXd> measured;
  std::vector<Reference> reference;
  std::string recorded_with;  // the label of the controller that flew the recording
  std::string diverged;       // why the recording flight diverged (its samples up to then are kept); "" if it completed
  std::size_t size() const { return time.size(); }
};

// Flies `prepared` through `flight` (progress on `progress`) and keeps every sample. Throws
// thetad::Error when the flight diverged before the first sample.
RecordedSamples record_samples(const Flight& flight, PreparedController& prepared, Progress* progress = nullptr);

// A controller is timed at 1 kHz as it flies, on consecutive samples: its warm starts (the last
// P, the last input) come from the sample before, as in flight. The timed samples are `segments`
// runs of consecutive samples spread evenly over the flight, `samples` in all; before each run the
// controller steps through kSettleSamples samples untimed, so that no timed step starts from a
// state seconds away.
struct StepTimingOptions {
  int samples = 1000;        // timed calls per controller and pass
  int segments = 10;
  int warmup_passes = 1;     // passes over the samples before timing
  int repetitions = 5;       // timed passes per controller
  int cpu = -1;              // core to pin to; -1: the last core this process may use; -2: no pinning
  double budget_seconds = 1e-3;  // the controller period (1 kHz)
};

struct StepTiming {
  std::string label;
  std::string controller;
  std::vector<double> nanoseconds;  // every timed call, in call order
  double median = 0, p10 = 0, p90 = 0, p99 = 0, max = 0;  // ns
  // Whether one core keeps up at the budget in the worst case measured (max < budget).
  bool real_time = false;
};

struct StepTimingReport {
  std::vector<StepTiming> controllers;
  int cpu = -1;  // the core the timing ran on (-1: not pinned)
  std::size_t samples = 0;  // timed per pass
  StepTimingOptions options;
};

inline constexpr std::size_t kSettleSamples = 10;

// Times each prepared controller on `samples` (each pass starts with a reset at `initial_state`).
// Throws thetad::Error when a controller fails on a recorded state.
StepTimingReport time_steps(std::vector<PreparedController>& controllers, const RecordedSamples& samples,
                            const Eigen::VectorXd& initial_state, Eigen::Index input_dim,
                            const StepTimingOptions& options);

// The report as a table (median, p10, p90, p99, max in µs, share of the budget, verdict).
std::string step_timing_table(const StepTimingReport& report);
nlohmann::ordered_json to_json(const StepTimingReport& report);

}  // namespace thetad
