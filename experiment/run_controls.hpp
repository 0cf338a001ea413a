#pragma once

#include <cstdint>
#include <optional>

#include "core/sim/simulator.hpp"

namespace thetad {

// What a front end may change about a scenario's flight without editing its file (the command
// line's --duration, --dt, ...). Unset keeps what the scenario says.
struct RunControls {
  std::optional<double> duration;        // s, in (0, one simulated day]
  std::optional<double> dt;              // plant step (s); must divide the controller period
  std::optional<int> log_every;          // log every N-th controller sample
  std::optional<std::uint64_t> seed;
  bool ideal = false;                    // no parameter uncertainty, noise or wind
  // Each disturbance on its own (after `ideal`): replays and sweeps set them one by one.
  std::optional<bool> parameter_uncertainty, wind_gust, measurement_noise, actuator_noise, wind_noise,
      induced_velocity_noise;
  std::optional<bool> actuator_limits;   // servo magnitude and rate limits (sim::ActuatorLimits)
  std::optional<bool> summary_only;      // true: no log, the summary only
  std::optional<bool> timing;            // false: no wall-clock figure anywhere (byte-identical reruns)
};

// `settings` with `controls` applied. The controller keeps sampling at the scenario's period with
// zero-order hold, so a new dt must divide that period: otherwise thetad::Error names both.
void apply(const RunControls& controls, sim::SimulationSettings& settings);

}  // namespace thetad
