#include "core/sim/simulation_settings.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "core/helicopter/uncertainty.hpp"

namespace thetad::sim {

std::int64_t SimulationSettings::samples() const {
  return static_cast<std::int64_t>(std::llround(duration / controller_period()));
}

void SimulationSettings::validate() const {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw Error("simulate: dt must be positive and finite");
  if (controller_period_steps < 1) throw Error("simulate: controller_period_steps must be at least 1");
  if (log_every < 1) throw Error("simulate: log_every must be at least 1");
  if (!(duration >= controller_period()) || !(duration <= kMaxDuration))
    throw Error("simulate: duration must be at least one controller period and at most " +
                std::to_string(static_cast<int>(kMaxDuration)) + " s (one simulated day)");
  heli::check_uncertainty_scale(uncertainty_scale);
  if (!parameter_deviations.empty()) heli::parameter_draw(parameter_deviations);
  if (!(noise.scale >= 0.0) || !std::isfinite(noise.scale))
    throw Error("simulate: the noise scale must be finite and non-negative");
  if (duration / controller_period() > 1e10)
    throw Error("simulate: the controller period is too short for the duration (more than 1e10 samples)");
  if (actuator_limits.enabled) actuator_limits.validate();
  turbulence.validate();
  for (const DiscreteGust& gust : discrete_gusts) gust.validate();
  sensor_noise.validate();
  servos.validate();
  computer.validate();
  if (computer.latency == FlightComputerSettings::Latency::measured && !measure_compute_time)
    throw Error("simulate: the flight computer's measured latency needs the step times measured (timing on)");
}

void SimulationSettings::check_memory(std::size_t log_columns) const {
  // The log is held whole: bounded here, so that a flight too long to log fails before it flies,
  // with advice, instead of with bad_alloc hours in.
  const std::int64_t run_samples = samples();
  const std::int64_t rows = keep_log ? (run_samples + log_every - 1) / log_every : 0;
  const double bytes =
      8.0 * static_cast<double>(rows * static_cast<std::int64_t>(log_columns) + (measure_compute_time ? run_samples : 0));
  if (bytes <= kMaxRunMemory) return;
  char advice[320];
  std::snprintf(advice, sizeof advice,
                "simulate: this flight's log would need %.1f GiB (%lld logged samples), more than the %.0f GiB a run "
                "may hold: log every N-th sample (log_every, --log-every) or only the summary (--summary-only)",
                bytes / (1 << 30), static_cast<long long>(rows), kMaxRunMemory / (1 << 30));
  throw Error(advice);
}

SimulationSettings SimulationSettings::paper() {
  SimulationSettings settings;
  settings.actuator_limits.enabled = false;
  return settings;
}

SimulationSettings SimulationSettings::ideal() {
  SimulationSettings settings;
  settings.parameter_uncertainty = false;
  settings.wind_gust.enabled = false;
  settings.noise.measurement = false;
  settings.noise.actuator = false;
  settings.noise.wind_component = false;
  settings.noise.induced_velocity = false;
  settings.actuator_limits.enabled = false;
  return settings;
}

}  // namespace thetad::sim
