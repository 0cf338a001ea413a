#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "core/control_law.hpp"
#include "experiment/flight.hpp"
#include "experiment/host_conditions.hpp"

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
  // How the recording flight ended, and why when it did not complete (its samples up to then are kept).
  sim::RunStatus status = sim::RunStatus::completed;
  std::string reason;
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
// The passes repeat until every controller's median is settled (settled_median) or 3 ×
// `repetitions` passes have run; the report says which.
struct StepTimingOptions {
  int samples = 1000;        // timed calls per controller and pass
  int segments = 10;
  int warmup_passes = 1;     // passes over the samples before timing
  int repetitions = 5;       // timed passes per controller, at least
  int cpu = -1;              // core to pin to; -1: the last core this process may use; -2: no pinning
  double budget_seconds = 1e-3;  // the controller period (1 kHz)
};

// Whether one core keeps up with the controller period, decided on a high percentile with a
// margin and on the share of calls over the period, so that an isolated preemption does not flip
// it and two runs near the boundary do not disagree:
//   capable:     p99 ≤ kCapableShare × budget and at most kOverrunShare of the calls over it;
//   not capable: p99 over the budget;
//   marginal:    in between.
enum class RealTimeVerdict { capable, marginal, not_capable };
inline constexpr double kCapableShare = 0.5;
inline constexpr double kOverrunShare = 1e-3;
// A median is settled when the medians of the first and the second half of the passes differ by at
// most kStableDrift of it, or by the clock's resolution for steps that short.
inline constexpr double kStableDrift = 0.03;
inline constexpr double kTimerResolutionNs = 50.0;
// The verdict for a 99th percentile `p99` and a share of calls over the budget (p99 and budget in
// one unit).
RealTimeVerdict real_time_verdict(double p99, double overrun_share, double budget);
const char* verdict_name(RealTimeVerdict verdict);

struct StepTiming {
  std::string label;
  std::string controller;
  std::vector<double> nanoseconds;  // every timed call, in call order
  double median = 0, p10 = 0, p90 = 0, p99 = 0, max = 0;  // ns
  std::size_t overruns = 0;          // calls over the budget
  double median_drift = 0;           // |median of the second half of the passes − of the first| (ns)
  double iterations_mean = 0;        // ControlLaw::last_iterations() per timed call (0: closed form)
  RealTimeVerdict verdict = RealTimeVerdict::not_capable;
};

// Whether the median of `timing` settled (kStableDrift).
bool settled_median(const StepTiming& timing);

struct StepTimingReport {
  std::vector<StepTiming> controllers;
  int cpu = -1;  // the core the timing ran on (-1: not pinned)
  std::size_t samples = 0;  // timed per pass
  int repetitions = 0;      // passes run per controller
  bool stable = false;      // every controller's median settled
  StepTimingOptions options;
  HostConditions host;      // what the host did meanwhile
};

inline constexpr std::size_t kSettleSamples = 10;

// Times each prepared controller on `samples` (each pass starts with a reset at `initial_state`).
// Throws thetad::Error when a controller fails on a recorded state.
StepTimingReport time_steps(std::vector<PreparedController>& controllers, const RecordedSamples& samples,
                            const Eigen::VectorXd& initial_state, Eigen::Index input_dim,
                            const StepTimingOptions& options);

// The report as a table (median, p10, p90, p99, max in µs, share of the budget, verdict), then
// the host's conditions and a warning when it was loaded or a median did not settle.
std::string step_timing_table(const StepTimingReport& report);
nlohmann::ordered_json to_json(const StepTimingReport& report);

// bench.json: the report with the recording (who flew it, how it ended) and the flight's
// provenance stamped with the host and the time. Its "format_version" says which names it has:
//   1 (no "format_version"): per controller median_ns, p10_ns, p90_ns, p99_ns, max_ns;
//      "recording_diverged" (the reason, "" when the recording completed).
//   2: the names of docs/glossary.md: step_time_{median,p10,p90,p99,max}_us (µs); "recording_status"
//      (completed, diverged, failed) and "recording_reason".
inline constexpr const char* kBenchFormat = "thetad-bench-1";
inline constexpr int kBenchFormatVersion = 2;
nlohmann::ordered_json bench_json(const Flight& flight, const RecordedSamples& samples, const StepTimingReport& report);

}  // namespace thetad
