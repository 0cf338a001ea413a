#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/sim/simulation_settings.hpp"
#include "settings/disturbance_blocks.hpp"

namespace thetad {

// What a front end may change about a scenario's flight without editing its file (the command
// line's --duration, --dt, ...), and what a scenario file says about its flight (Scenario::
// simulation): the members the run settings' table (settings/run_settings.hpp) sets. Unset keeps
// what the scenario (or, for a file, thetad's default) says.
struct RunControls {
  std::optional<double> duration;        // s, in (0, one simulated day]
  std::optional<double> dt;              // plant step (s); must divide the controller period
  // With dt, the controller period in plant steps (a file's pair): dt is then taken as it is.
  std::optional<int> controller_period_steps;
  std::optional<int> log_every;          // log every N-th controller sample
  std::optional<std::uint64_t> seed;
  bool ideal = false;                    // no parameter uncertainty, noise, wind, servo dynamics or limits
  // Each disturbance on its own (after `ideal`): replays and sweeps set them one by one.
  std::optional<bool> parameter_uncertainty, wind_gust, measurement_noise, actuator_noise, wind_noise,
      induced_velocity_noise;
  std::optional<sim::MeasurementNoiseOn> measurement_noise_on;
  std::optional<bool> actuator_limits;   // servo magnitude and rate limits (sim::ActuatorLimits)
  std::optional<bool> anti_windup;       // conditional integration of the position integrals at the limits
  // Strengths of the disturbances (campaign sweeps): multipliers of the paper's setting.
  std::optional<double> uncertainty_scale;  // Table 1's parameter bounds (0 nominal, 1 the paper's)
  std::optional<double> noise_scale;        // every sensor, actuator, wind and induced-velocity noise level
  std::optional<double> gust_scale;         // the whole wind: mean and gust deviations
  std::optional<double> gust_onset;         // s: calm air before it
  // Table 1's 21 parameter deviations xi in [-1, 1] instead of the draw (a worst case, docs/robustness.md).
  std::optional<std::vector<double>> parameter_deviations;
  // The disturbances beyond the paper (docs/model.md §15), whole blocks in place of the scenario's
  // (a replay sets them as recorded) ...
  DisturbanceBlocks beyond_paper;
  // ... then single fields of them (campaign factors).
  std::optional<sim::TurbulenceSettings::Model> turbulence_model;
  std::optional<sim::TurbulenceIntensity> turbulence_intensity;
  std::optional<double> turbulence_scale;
  std::optional<int> servo_delay_samples;
  std::optional<double> servo_time_constant;  // s, every input
  // The flight computer's slowdown (docs/model.md §15.7): for a latency measured or step-time.
  std::optional<double> slowdown;
  // Added to the scenario's initial position (m, north-east-down): the flight starts off the trajectory.
  std::optional<Eigen::Vector3d> initial_offset;
  // Added to the scenario's initial Euler angles (rad: roll φ, pitch θ, yaw ψ): the flight starts tilted.
  std::optional<Eigen::Vector3d> initial_attitude_offset;
  // The scenario's trajectory flown this many times faster (Scenario::at_speed): the same path in
  // 1/s of the time, the flight's duration included. `duration`, when also given, is the flown time.
  std::optional<double> speed_scale;
  // rad: the scenario's trajectory turned about its start (Scenario::turned), north towards east.
  std::optional<double> course;
  // A plant's flight (docs/plants.md): its own settings over its scenario's plant_settings block
  // (the factors plant.NAME), and entries of its initial state by index (initial_state.I).
  std::map<std::string, double> plant_settings;
  std::map<int, double> initial_state_entries;
  std::optional<bool> summary_only;      // true: no log, the summary only
  std::optional<bool> timing;            // false: no wall-clock figure anywhere (byte-identical reruns)
};

// `settings` with `controls` applied, then the whole checked (SimulationSettings::validate). The
// controller keeps sampling at the scenario's period with zero-order hold, so a new dt must divide
// that period: otherwise thetad::Error names both. A scale or onset out of range is an error naming
// it. (The initial offsets act on the initial state and speed_scale and course on the scenario:
// Flight.)
void apply(const RunControls& controls, sim::SimulationSettings& settings);
// The same without the final check: a scenario file's controls, which the file's reader checks
// naming its fields.
void fly(const RunControls& controls, sim::SimulationSettings& settings);

// `initial_state` moved by controls.initial_offset and turned by controls.initial_attitude_offset
// (unchanged without them); a non-finite offset is an error.
Eigen::VectorXd offset_initial_state(const RunControls& controls, const Eigen::VectorXd& initial_state);

}  // namespace thetad
