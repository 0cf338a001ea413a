#include "core/sim/simulator.hpp"

#include <chrono>
#include <optional>
#include <random>
#include <string>

#include "core/error.hpp"
#include "core/plant_code_error.hpp"
#include "core/sim/rk4.hpp"
#include "core/sim/run_metrics.hpp"
#include "core/sim/worst_certificates.hpp"

namespace thetad::sim {

namespace {

// control() of `law`; its wall time (ns) when `timing`, else 0.
std::int64_t call_control(ControlLaw& law, double t, const Eigen::VectorXd& measured, const Reference& reference,
                          Eigen::VectorXd& command, bool timing) {
  if (!timing) {
    law.control(t, measured, reference, command);
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  law.control(t, measured, reference, command);
  const auto stop = std::chrono::steady_clock::now();
  return std::chrono::duration_cast<std::chrono::nanoseconds>(stop - start).count();
}

// The controller period's RK4 steps from t: `previous` (the input acting before this period) up to
// `arrival` into the period, `applied` from there (zero-order hold); the plant step that the arrival
// falls in is split there. On divergence, t becomes the end of the step that diverged and the
// reason is returned; `code_failed` says whether the plant's code failed (PlantCodeError).
std::optional<std::string> hold_for_one_period(const SdcPlant& plant, Disturbances& disturbances,
                                               const Eigen::VectorXd& previous, const Eigen::VectorXd& applied,
                                               double arrival, const SimulationSettings& settings,
                                               Rk4Workspace& workspace, Eigen::VectorXd& x, double& t,
                                               bool& code_failed) {
  for (int step = 1; step <= settings.controller_period_steps; ++step) {
    const double t_end = t + step * settings.dt;
    const double begins = (step - 1) * settings.dt, ends = step * settings.dt;
    std::optional<std::string> failure;
    try {
      if (arrival <= begins) {
        rk4_step(plant, applied, settings.dt, workspace, x);
      } else if (arrival >= ends) {
        rk4_step(plant, previous, settings.dt, workspace, x);
      } else {
        rk4_step(plant, previous, arrival - begins, workspace, x);
        rk4_step(plant, applied, ends - arrival, workspace, x);
      }
      failure = disturbances.check(x, t_end);
    } catch (const Error& error) {
      failure = failure_reason("plant", error, t_end);
      code_failed = dynamic_cast<const PlantCodeError*>(&error) != nullptr;
    }
    if (failure) {
      t = t_end;
      return failure;
    }
    disturbances.advance(t_end, settings.dt, x);
  }
  return std::nullopt;
}

// The tracked states' errors (true state minus command) into `error`, and the same padded with
// zeros to three entries, as the reference's position is.
void tracking_error(const std::vector<TrackedState>& tracked, const Eigen::VectorXd& x, const Eigen::Vector3d& command,
                    Eigen::VectorXd& error, Eigen::Vector3d& padded) {
  padded.setZero();
  for (std::size_t i = 0; i < tracked.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    padded[k] = error[k] = x[tracked[i].index] - command[k];
  }
}

// The law's columns of its last step into `values`, one per column (checked: a plug-in's miscount
// would shift the log's columns), and its certificates into the run's worst.
void take_law_columns(const ControlLaw& law, double t, std::size_t columns, std::vector<double>& values,
                       WorstCertificates& worst) {
  values.clear();
  law.log_values(values);
  if (values.size() != columns)
    throw Error("log_values gave " + std::to_string(values.size()) + " values for " + std::to_string(columns) +
                " log columns");
  worst.add(t, values);
}

// What the flight computer did at one sample, for the log.
struct ComputerSample {
  double latency = 0.0;  // s, of the computation started at the sample (0 when none started)
  bool skipped = false;  // the computer was busy: no computation started
};

// One log row, in the order of log_schema().
void append_row(double t, const std::vector<TrackedState>& tracked, const Eigen::Vector3d& command_position,
                const Eigen::VectorXd& x, const Eigen::VectorXd& measured, const Eigen::VectorXd& command,
                const Eigen::VectorXd& applied, const Disturbances& disturbances, const ComputerSample* computer,
                const std::vector<double>& law_values, std::int64_t compute_ns, RunLog& log) {
  auto& row = log.values;
  row.push_back(t);
  row.insert(row.end(), command_position.begin(), command_position.begin() + static_cast<Eigen::Index>(tracked.size()));
  row.insert(row.end(), x.begin(), x.end());
  row.insert(row.end(), measured.begin(), measured.end());
  row.insert(row.end(), command.begin(), command.end());
  row.insert(row.end(), applied.begin(), applied.end());
  disturbances.log_values(row);
  if (computer) {
    row.push_back(computer->latency);
    row.push_back(computer->skipped ? 1.0 : 0.0);
  }
  row.insert(row.end(), law_values.begin(), law_values.end());
  row.push_back(static_cast<double>(compute_ns));
}

}  // namespace

std::vector<LogColumn> log_schema(const SdcPlant& plant, const Disturbances& disturbances,
                                  const std::vector<ControllerColumn>& law_columns, bool computer) {
  std::vector<LogColumn> columns{{"t", "s"}};
  for (const auto& tracked : plant.tracked_states()) columns.push_back(tracked.command);
  const std::vector<LogColumn> states = plant.state_columns(), inputs = plant.input_columns();
  columns.insert(columns.end(), states.begin(), states.end());
  for (const auto& [name, unit] : states) columns.push_back({"meas_" + name, unit});
  for (const auto& [name, unit] : inputs) columns.push_back({"cmd_" + name, unit});
  for (const auto& [name, unit] : inputs) columns.push_back({"app_" + name, unit});
  for (auto& column : disturbances.log_columns()) columns.push_back(std::move(column));
  if (computer) {
    columns.push_back({"computation_latency", "s"});
    columns.push_back({"sample_skipped", ""});
  }
  for (const auto& law_column : law_columns) columns.push_back(law_column.column);
  columns.push_back(step_time_column());
  return columns;
}

LogLayout log_layout(const SdcPlant& plant) {
  const auto state = static_cast<Eigen::Index>(1 + plant.tracked_states().size());
  const Eigen::Index n = plant.state_dim(), m = plant.input_dim();
  return {state, state + n, state + 2 * n, state + 2 * n + m};
}

RunResult simulate(ControlLaw& law, Disturbances& disturbances, const ReferenceTrajectory& reference,
                   const Eigen::VectorXd& x0, const SimulationSettings& settings,
                   const std::function<void(double t)>& progress, DeviationCost* deviation) {
  settings.validate();
  std::mt19937_64 rng(settings.seed);
  const SdcPlant& plant = disturbances.start(rng);
  const Eigen::Index n = plant.state_dim(), m = plant.input_dim();
  if (x0.size() != n)
    throw Error("simulate: x0 has " + std::to_string(x0.size()) + " entries, the plant has " + std::to_string(n));
  const std::vector<TrackedState> tracked = plant.tracked_states();
  if (tracked.size() > 3) throw Error("simulate: a plant tracks at most three states (the reference's position)");

  RunResult result;
  const std::vector<ControllerColumn> law_columns = law.log_columns();
  const bool computer_in_loop = settings.computer.active();
  if (settings.computer.latency == FlightComputerSettings::Latency::step_time && !(settings.computer.step_time > 0.0))
    throw Error("simulate: the flight computer's step-time latency has no step time for " + law.name() +
                " (a Flight takes it from the step times by the controller's label)");
  result.log.columns = log_schema(plant, disturbances, law_columns, computer_in_loop);
  settings.check_memory(result.log.columns.size());
  const double period = settings.controller_period();
  const std::int64_t samples = settings.samples();
  const std::int64_t rows = settings.keep_log ? (samples + settings.log_every - 1) / settings.log_every : 0;
  result.log.values.reserve(static_cast<std::size_t>(rows) * result.log.columns.size());
  RunSummary& summary = result.summary;
  summary.controller = law.name();
  summary.settings = settings;
  summary.tracked = tracked;
  summary.inputs = plant.input_columns();
  summary.saturation = SaturationCounts::none(static_cast<int>(m));

  // J with the weights the controllers are designed with (the helicopter: Eq. 32, Eqs. 33-34).
  const DesignDefaults design = plant.design_defaults();
  RunMetrics metrics(design.state_weights, design.input_weights, static_cast<Eigen::Index>(tracked.size()), period,
                     samples, settings.measure_compute_time);

  Eigen::VectorXd x = x0;
  Eigen::VectorXd measured(n), command(m), delivered(m), applied(m), previous(m), v(n),
      error(static_cast<Eigen::Index>(tracked.size()));
  previous.setZero();  // acts only after a late arrival, and the first arrival is at t0
  Eigen::Vector3d padded_error;
  Rk4Workspace workspace(n);
  PositionIntegral reference_integral, true_error_integral;
  std::vector<double> law_values;
  law_values.reserve(law_columns.size());
  WorstCertificates worst_certificates(law_columns);
  FlightComputer computer(settings.computer, period);
  ComputerSample computer_sample;

  std::optional<std::string> failure = disturbances.check(x, 0.0);
  bool controller_failed = false;
  bool code_failed = false;  // the plant's (PlantCodeError)
  try {
    law.reset(x0, 0.0);
  } catch (const std::exception& error) {
    failure = failure_reason("controller", error, 0.0);
    controller_failed = true;
  }
  double t = 0.0;
  for (std::int64_t k = 0; k < samples && !failure; ++k) {
    t = static_cast<double>(k) * period;
    if (progress && k % kProgressSamples == 0) progress(t);
    disturbances.sample(t, x, rng);
    const Reference now{reference.position(t), reference_integral.value, reference.velocity(t),
                        reference.acceleration(t)};
    disturbances.measure(x, now, measured);

    // The flight computer (docs/model.md §15.7): without it, every sample computes and its input
    // arrives at once, and `delivered` is `command`.
    std::int64_t elapsed_ns = 0;
    computer_sample = {0.0, !computer.free_at(k)};
    if (computer_sample.skipped) {
      computer.skip();
    } else {
      try {
        elapsed_ns = call_control(law, t, measured, now, command, settings.measure_compute_time);
        if (!command.allFinite()) throw Error("non-finite command");
        if (!law_columns.empty())
          take_law_columns(law, t, law_columns.size(), law_values, worst_certificates);
      } catch (const std::exception& error) {
        // Whatever a user's controller throws (a plug-in's own exception types too) ends this run,
        // not the program: the other runs of a comparison go on.
        failure = failure_reason("controller", error, t);
        controller_failed = true;
        break;
      }
      computer_sample.latency = computer.start(k, elapsed_ns);
    }
    const std::optional<double> arrival = computer.arrival(k);
    if (arrival) delivered = command;
    failure = disturbances.actuate(t, x, delivered, applied);
    if (failure) break;

    tracking_error(tracked, x, now.position, error, padded_error);
    plant.true_tracking_vector(x, now, true_error_integral.value, v);
    metrics.add(error, v, delivered, computer_sample.skipped ? -1 : elapsed_ns);
    if (deviation) deviation->add(x, now, v, delivered);
    if (settings.keep_log && k % settings.log_every == 0)
      append_row(t, tracked, now.position, x, measured, delivered, applied, disturbances,
                 computer_in_loop ? &computer_sample : nullptr, law_values, elapsed_ns, result.log);

    // Anti-windup (ActuatorLimits::anti_windup): held, the command's integral follows the measured
    // position, so that the measured-minus-command integral the controllers see does not move.
    if (settings.actuator_limits.enabled && settings.actuator_limits.anti_windup && disturbances.input_limited()) {
      Eigen::Vector3d held = now.position;
      for (std::size_t i = 0; i < tracked.size(); ++i) held[static_cast<Eigen::Index>(i)] = measured[tracked[i].index];
      reference_integral.accumulate(held, period);
    } else {
      reference_integral.accumulate(now.position, period);
    }
    true_error_integral.accumulate(padded_error, period);

    failure = hold_for_one_period(plant, disturbances, previous, applied, arrival.value_or(0.0), settings, workspace,
                                  x, t, code_failed);
    previous = applied;
  }

  if (failure) {
    summary.status = controller_failed || code_failed ? RunStatus::failed : RunStatus::diverged;
    summary.reason = *failure;
    summary.end_time = t;
  } else {
    summary.end_time = static_cast<double>(samples) * period;
  }
  metrics.finish(summary);
  if (deviation) {
    summary.cost_dev = deviation->value();
    summary.cost_dev_weights = deviation->weights().name;
  }
  disturbances.finish(summary);
  summary.controller_counters = law.counters();
  summary.certificates = worst_certificates.worst();
  if (computer_in_loop) summary.computer = computer.counts();
  return result;
}

}  // namespace thetad::sim
