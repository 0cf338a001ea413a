#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/helicopter/helicopter.hpp"
#include "core/control_law.hpp"
#include "core/sim/actuator_limits.hpp"
#include "core/sim/noise.hpp"
#include "core/sim/wind_gust.hpp"

namespace thetad::sim {

// Where a run is declared diverged (spec §8.4). The run stops at the first RK4 step whose state
// breaks one of these; nothing after it is logged.
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
  WindGustSettings wind_gust;
  NoiseSettings noise;
  DivergenceLimits limits;
  // Servo magnitude and rate limits on the applied input: the X-Cell's (docs/model.md §12), on
  // unless turned off; the paper's setting has none.
  ActuatorLimits actuator_limits = ActuatorLimits::x_cell();
  // Off makes the compute_ns column and the timing statistics 0, so that two runs with the same
  // seed give byte-identical files (the only non-deterministic quantity of a run is its timing).
  bool measure_compute_time = true;
  std::uint64_t seed = 1;

  double controller_period() const { return dt * controller_period_steps; }
  // Throws thetad::Error naming the first setting out of range, or with advice when the run's log
  // would hold more than kMaxRunMemory.
  void validate() const;

  // One simulated day: longer flights are a mistake in a file, not a study.
  static constexpr double kMaxDuration = 86400.0;
  // What one run's log and timing samples may hold in memory (bytes): 2 GiB, about 75 minutes of
  // flight logged at every 1 kHz sample (60 columns). Beyond it simulate() refuses up front.
  static constexpr double kMaxRunMemory = 2.0 * (1 << 30);

  // Every disturbance on and no actuator limits: the paper's setting (spec §8.1).
  static SimulationSettings paper();
  // Every disturbance off and no actuator limits: the nominal plant with ideal servos, no wind, no
  // noise.
  static SimulationSettings ideal();
};

// One column of the run log: CSV header "name_unit".
struct LogColumn {
  std::string name;
  std::string unit;
  std::string header() const { return name + "_" + unit; }
};

// The run log's columns, in order: the single definition that the CSV header, the row writer
// and any reader of the files check against.
const std::vector<LogColumn>& log_schema();

// The logged controller samples, row-major, log_schema().size() values per row. Reserved for the
// whole run before the first step (none for a summary-only run).
struct RunLog {
  std::vector<double> values;

  Eigen::Index rows() const { return static_cast<Eigen::Index>(values.size() / log_schema().size()); }
  Eigen::Map<const Eigen::VectorXd> row(Eigen::Index i) const {
    const auto columns = static_cast<Eigen::Index>(log_schema().size());
    return {values.data() + i * columns, columns};
  }
};

// diverged: the state left the divergence limits or the plant failed; failed: the controller threw
// or returned a non-finite command (a fault of the controller, not of the closed loop).
enum class RunStatus { completed, diverged, failed };

// Throws thetad::Error with advice (log every N-th sample, or only the summary) when a run would
// hold more than SimulationSettings::kMaxRunMemory bytes of log (`logged_rows` rows in `bytes`).
void check_run_memory(double bytes, std::int64_t logged_rows);

// "completed", "diverged" or "failed", as result files write it.
const char* status_name(RunStatus status);

struct RunSummary {
  std::string controller;
  SimulationSettings settings;
  RunStatus status = RunStatus::completed;
  std::string reason;     // why the run diverged or failed (with the time); empty when completed
  double end_time = 0.0;  // duration when completed, else the time it diverged or failed (s)
  std::string model_options;  // heli::ModelOptions::to_string() of the plant
  // The Table 1 parameter factors p_true / p_nom of this run, in table order; empty when
  // parameter_uncertainty is off.
  std::vector<std::pair<std::string, double>> parameter_factors;
  std::int64_t controller_samples = 0;  // samples whose control was computed
  // The controller's own event counts at the end of the run (ControlLaw::counters()).
  std::vector<std::pair<std::string, double>> controller_counters;
  // True position minus reference over the controller samples (m).
  Eigen::Vector3d rms_tracking_error = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_tracking_error = Eigen::Vector3d::Zero();
  // Control effort: RMS of the commanded input per channel over the controller samples
  // (N, rad, rad, rad, rad). Commanded, not applied: it measures the controller, not the noise.
  Eigen::Matrix<double, 5, 1> command_rms = Eigen::Matrix<double, 5, 1>::Zero();
  // Controller samples whose applied input the actuator limits changed, per channel (none when off).
  SaturationCounts saturation;
  // J = 1/2 sum_k (V_track^T Q V_track + u^T R u) T_c (Eq. 32 on V_track, Q and R of §7.2), with the
  // true V_track (integral entries by the PositionIntegral rule on the true position error) and
  // the commanded u, by left rectangles at the controller rate.
  double cost = 0.0;
  // Wall time of the control() call per sample (ns); 0 when not measured.
  double compute_ns_mean = 0.0;
  double compute_ns_median = 0.0;
  double compute_ns_p99 = 0.0;
};

struct RunResult {
  RunSummary summary;
  RunLog log;
};

// Flies `law` on the helicopter from x0 (the 18-state, s = 1) for settings.duration.
//
// One std::mt19937_64 seeded with settings.seed drives everything, in this order: the Table 1
// parameters (heli::perturbed_parameters, once), then per controller sample the
// SampleDraws::kCount normals of SampleDraws::draw. All draws are taken whatever the switches say,
// so the same seed gives the same disturbance realization for every controller and every subset
// of disturbances, and bit-identical results for the same settings.
//
// Per controller sample k at t_k = k T_c: draw; gust and environment (held for the sample);
// measure; control() (timed); actuator noise; actuator limits; log; then controller_period_steps RK4 steps of dt
// with the applied input held. Divergence (DivergenceLimits, non-finite state, command or rotor
// speed, or a thetad::Error from the plant or the controller) ends the run with status diverged.
// Throws thetad::Error for invalid settings or a wrongly sized x0. `progress`, when given, is called
// with the simulated time every kProgressSamples controller samples (progress displays).
inline constexpr std::int64_t kProgressSamples = 100;
RunResult simulate(ControlLaw& law, const ReferenceTrajectory& reference, const Eigen::VectorXd& x0,
                   const SimulationSettings& settings,
                   const heli::Parameters& nominal = heli::Parameters::nominal(),
                   const heli::ModelOptions& options = heli::ModelOptions::resolved(),
                   const std::function<void(double t)>& progress = {});

}  // namespace thetad::sim
