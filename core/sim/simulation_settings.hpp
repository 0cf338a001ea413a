#pragma once

#include <cstdint>
#include <numbers>

#include <vector>

#include "core/sim/actuator_limits.hpp"
#include "core/sim/discrete_gust.hpp"
#include "core/sim/flight_computer.hpp"
#include "core/sim/noise.hpp"
#include "core/sim/sensor_noise.hpp"
#include "core/sim/servo_dynamics.hpp"
#include "core/sim/turbulence.hpp"
#include "core/sim/wind_gust.hpp"

namespace thetad::sim {

// Where a helicopter run is declared diverged (docs/model.md §8). The run stops at the first RK4
// step whose state breaks one of these; nothing after it is logged.
struct DivergenceLimits {
  double max_attitude = 85.0 * std::numbers::pi / 180.0;         // |phi|, |theta| (rad)
  double max_body_rate = 20.0;                                   // |p|, |q|, |r| (rad/s)
  double max_speed = 50.0;                                       // |(u, v, w)| (m/s)
  double max_ground_penetration = 1.0;                           // z_p (m): 1 m below the ground
};

struct SimulationSettings {
  double dt = 1e-3;                 // RK4 step (s), A-18
  int controller_period_steps = 1;  // controller, noise and gust period as a multiple of dt
  int log_every = 1;                // log every k-th controller sample
  bool keep_log = true;             // false: the summary alone (no RunLog rows)
  double duration = 10.0;           // s, at most kMaxDuration; the run has round(duration / T_c) controller samples
  bool parameter_uncertainty = true;  // Table 1 parameters drawn once per run
  // Multiplies Table 1's parameter bounds (heli::perturbed_parameters): 0 nominal, 1 the paper's, 2 twice.
  double uncertainty_scale = 1.0;
  // Table 1's 21 parameter deviations xi in [-1, 1], in table order, flown instead of the run's draw
  // (a worst case found by a search, and its replays); empty: drawn. The draw is taken either way,
  // so every later random number is the same.
  std::vector<double> parameter_deviations;
  WindGustSettings wind_gust;
  NoiseSettings noise;
  // The disturbances beyond the paper's (docs/model.md §15), each off by default and drawing from
  // its own stream (RandomStream): turbulence at the plant rate, 1 - cosine gusts, additive sensor
  // noise with a stated spectrum, servo lag and transport delay.
  TurbulenceSettings turbulence;
  std::vector<DiscreteGust> discrete_gusts;
  SensorNoiseSettings sensor_noise;
  ServoSettings servos;
  // When each computed input reaches the servos (docs/model.md §15.7): none by default.
  FlightComputerSettings computer;
  DivergenceLimits limits;
  // Servo magnitude and rate limits on the applied input: the X-Cell's (docs/model.md §12), on
  // unless turned off; the paper's setting has none.
  ActuatorLimits actuator_limits = ActuatorLimits::x_cell();
  // Off makes the in_flight_step_time_ns column and the timing statistics 0, so that two runs with the same
  // seed give byte-identical files (the only non-deterministic quantity of a run is its timing).
  bool measure_compute_time = true;
  std::uint64_t seed = 1;

  double controller_period() const { return dt * controller_period_steps; }
  // The run's controller samples: round(duration / T_c).
  std::int64_t samples() const;
  // Throws thetad::Error naming the first setting out of range.
  void validate() const;
  // Throws thetad::Error with advice when a run whose log has `log_columns` columns would hold
  // more than kMaxRunMemory (its log and its timing samples).
  void check_memory(std::size_t log_columns) const;

  // One simulated day: longer flights are a mistake in a file, not a study.
  static constexpr double kMaxDuration = 86400.0;
  // What one run's log and timing samples may hold in memory (bytes): 2 GiB, about 75 minutes of
  // flight logged at every 1 kHz sample of the helicopter (60 columns). Beyond it simulate()
  // refuses up front.
  static constexpr double kMaxRunMemory = 2.0 * (1 << 30);

  // Every disturbance on and no actuator limits: the paper's setting (docs/model.md §8).
  static SimulationSettings paper();
  // Every disturbance off (§15's too) and no actuator limits: the nominal plant with ideal servos,
  // no wind, no noise.
  static SimulationSettings ideal();
};

}  // namespace thetad::sim
