#include "core/sim/flight_computer.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace thetad::sim {

namespace {

// Sample times and latencies are compared to within this share of the period, so that a latency
// of exactly one period arrives at the next sample, not just before it.
constexpr double kTimeTolerance = 1e-9;

}  // namespace

void FlightComputerSettings::validate() const {
  if (!(fixed >= 0.0) || !(fixed <= kMaxLatency))
    throw Error("simulate: the flight computer's fixed latency must be from 0 to 60 s");
  if (!(slowdown > 0.0) || !(slowdown <= kMaxSlowdown))
    throw Error("simulate: the flight computer's slowdown must be positive and at most 1e6");
  for (const auto& [controller, seconds] : step_times)
    if (!(seconds >= 0.0) || !(seconds <= kMaxLatency))
      throw Error("simulate: the flight computer's step time of " + controller + " must be from 0 to 60 s");
  if (!(step_time >= 0.0) || !(step_time <= kMaxLatency))
    throw Error("simulate: the flight computer's step time must be from 0 to 60 s");
  if (latency == Latency::step_time && step_times.empty() && step_time == 0.0)
    throw Error("simulate: the flight computer's step-time latency needs the controllers' step times (a bench file)");
}

double FlightComputerSettings::step_time_of(const std::string& label) const {
  const auto found = std::find_if(step_times.begin(), step_times.end(),
                                  [&label](const auto& entry) { return entry.first == label; });
  if (found == step_times.end()) {
    std::string known;
    for (const auto& entry : step_times) known += (known.empty() ? "" : ", ") + entry.first;
    throw Error("the flight computer has no step time for controller " + label + " (" + step_time_source +
                " gives " + known + "): bench the same controller specs");
  }
  return found->second;
}

FlightComputer::FlightComputer(const FlightComputerSettings& settings, double period)
    : latency_(settings.latency),
      overrun_(settings.overrun),
      fixed_(settings.fixed),
      slowdown_(settings.slowdown),
      step_time_(settings.step_time),
      period_(period) {}

bool FlightComputer::free_at(std::int64_t k) const {
  return static_cast<double>(k) * period_ >= busy_until_ - kTimeTolerance * period_;
}

double FlightComputer::start(std::int64_t k, std::int64_t wall_ns) {
  using Latency = FlightComputerSettings::Latency;
  double latency = 0.0;
  if (k > 0) {
    switch (latency_) {
      case Latency::none: break;
      case Latency::fixed: latency = fixed_; break;
      case Latency::measured: latency = slowdown_ * static_cast<double>(wall_ns) * 1e-9; break;
      case Latency::step_time: latency = slowdown_ * step_time_; break;
    }
  }
  ++counts_.computations;
  latency_sum_ += latency;
  counts_.max_latency = std::max(counts_.max_latency, latency);
  const double t = static_cast<double>(k) * period_;
  const bool missed = latency > period_ * (1.0 + kTimeTolerance);
  if (missed) {
    ++counts_.missed_deadlines;
    counts_.longest_missed_run = std::max(counts_.longest_missed_run, ++missed_run_);
  } else {
    missed_run_ = 0;
  }
  if (missed && overrun_ == FlightComputerSettings::Overrun::abort) {
    ++counts_.aborted;
    busy_until_ = t + period_;
    pending_ = false;
  } else {
    busy_until_ = ready_at_ = t + latency;
    pending_ = true;
  }
  return latency;
}

std::optional<double> FlightComputer::arrival(std::int64_t k) {
  const double t = static_cast<double>(k) * period_;
  if (!pending_ || ready_at_ >= t + period_ * (1.0 - kTimeTolerance)) return std::nullopt;
  pending_ = false;
  const double offset = ready_at_ - t;
  return offset <= kTimeTolerance * period_ ? 0.0 : offset;
}

ComputerCounts FlightComputer::counts() const {
  ComputerCounts counts = counts_;
  counts.mean_latency = counts_.computations > 0 ? latency_sum_ / static_cast<double>(counts_.computations) : 0.0;
  return counts;
}

}  // namespace thetad::sim
