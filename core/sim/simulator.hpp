#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "core/control_law.hpp"
#include "core/log_column.hpp"
#include "core/sim/deviation_cost.hpp"
#include "core/sim/disturbances.hpp"
#include "core/sim/run_log.hpp"
#include "core/sim/run_summary.hpp"
#include "core/sim/simulation_settings.hpp"

namespace thetad::sim {

struct RunResult {
  RunSummary summary;
  RunLog log;
};

// The columns of a run's log on `plant` with `disturbances`, in the order the row writer appends
// them: t; the commands of the tracked states; the true state; the measured state (meas_); the
// commanded input (cmd_); the applied input (app_); the disturbances' own columns; the
// controller's own columns and certificates (ControlLaw::log_columns), if any; the control step's
// wall time (in_flight_step_time_ns). With the flight computer in the loop (`computer`), its two
// columns come before the controller's: computation_latency_s and sample_skipped.
std::vector<LogColumn> log_schema(const SdcPlant& plant, const Disturbances& disturbances,
                                  const std::vector<ControllerColumn>& law_columns = {}, bool computer = false);
// Where log_schema() puts the plant's blocks: the first column of the true state, of the measured
// state, of the commanded input and of the applied input.
struct LogLayout {
  Eigen::Index state, measured, command, applied;
};
LogLayout log_layout(const SdcPlant& plant);

// The last column of every log: the control step's wall time in flight (docs/glossary.md "Compute
// time"), which the files of runs flown without timing leave out. Result files before format_version 4
// named it compute_ns (experiment/result_names.hpp).
inline LogColumn step_time_column() { return {"in_flight_step_time", "ns"}; }

// Flies `law` on the plant that disturbances.start() returns, from x0 for settings.duration: the one
// flight loop of every plant.
//
// One std::mt19937_64 seeded with settings.seed drives every paper draw, through `disturbances`
// (the later sources draw from their own streams, RandomStream). Per controller sample k at
// t_k = k T_c: the disturbances' sample(); the reference; measure(); control() (timed) unless the
// flight computer is busy (settings.computer, FlightComputer); actuate() of the command that reaches
// the servos in this period; metrics; log; then controller_period_steps RK4 steps of dt with the
// applied input held (zero-order hold; the previous period's until a late command arrives, the
// plant step it arrives in split there), each followed by check() and advance(). The reference's integral is
// accumulated by the PositionIntegral rule. A check() or actuate() that fails, or a thetad::Error
// from the plant ends the run as diverged; whatever the controller throws, a non-finite command, and
// a PlantCodeError from the plant (its code failed, core/plant_code_error.hpp), end it as failed.
// Throws thetad::Error for invalid settings, a log that would not fit in memory, or a wrongly sized
// x0. `progress`, when given, is called with the simulated time every kProgressSamples controller
// samples (progress displays).
inline constexpr std::int64_t kProgressSamples = 100;
// `deviation`, when given, scores the run (J_dev) at every controller sample.
RunResult simulate(ControlLaw& law, Disturbances& disturbances, const ReferenceTrajectory& reference,
                   const Eigen::VectorXd& x0, const SimulationSettings& settings,
                   const std::function<void(double t)>& progress = {}, DeviationCost* deviation = nullptr);

}  // namespace thetad::sim
