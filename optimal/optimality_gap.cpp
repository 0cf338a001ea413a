#include "optimal/optimality_gap.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "core/sim/run_metrics.hpp"

namespace thetad {

namespace {

using heli::kInputDim;
using heli::kStateDim;

Eigen::Index column(const std::string& header) {
  const auto& schema = sim::log_schema();
  const auto found = std::find_if(schema.begin(), schema.end(), [&](const auto& c) { return c.header() == header; });
  return static_cast<Eigen::Index>(found - schema.begin());
}

// Whole multiples of the controller period, or an error naming the option.
int periods_in(double seconds, double period, const char* what) {
  const double ratio = seconds / period;
  const auto whole = static_cast<int>(std::llround(ratio));
  if (!(whole >= 1) || std::abs(ratio - whole) > 1e-9 * ratio) {
    throw Error(std::string("optimality gap: the ") + what + " (" + std::to_string(seconds) +
                " s) is not a whole number of controller periods (" + std::to_string(period) + " s)");
  }
  return whole;
}

}  // namespace

OptimalControlProblem optimality_problem(const Flight& flight, const OptimalityOptions& options) {
  const sim::SimulationSettings& s = flight.settings();
  const sim::NoiseSettings& noise = s.noise;
  if (s.parameter_uncertainty || s.wind_gust.enabled || noise.measurement || noise.actuator || noise.wind_component ||
      noise.induced_velocity) {
    throw Error("optimality gap: the flight has disturbances (" + flight.disturbances() +
                "); the optimum is that of the nominal plant: fly it ideal");
  }
  if (s.actuator_limits.enabled)
    throw Error("optimality gap: the flight has actuator limits, which the optimal control problem does not model");
  if (!s.keep_log || s.log_every != 1)
    throw Error("optimality gap: the flights must log every controller sample (the warm start is read from the log)");
  const double period = s.controller_period();
  const int interval_periods = periods_in(options.control_interval, period, "control interval");
  const int samples = periods_in(s.duration, period, "horizon");
  if (samples % interval_periods != 0) {
    throw Error("optimality gap: the horizon (" + std::to_string(s.duration) +
                " s) is not a whole number of control intervals (" + std::to_string(options.control_interval) + " s)");
  }
  const DesignDefaults design = flight.model().design_defaults();
  OptimalControlProblem problem;
  problem.plant = &flight.model();
  problem.reference = &flight.scenario().trajectory;
  problem.initial_state = flight.initial_state();
  problem.state_weights = design.state_weights;
  problem.input_weights = design.input_weights;
  problem.dt = s.dt;
  problem.controller_period_steps = s.controller_period_steps;
  problem.interval_periods = interval_periods;
  problem.intervals = samples / interval_periods;
  problem.sampled_position_integral = heli::kXi;  // as simulate() prices J
  problem.validate();
  return problem;
}

namespace {

const RunResult& warm_start_flight(const std::vector<RunResult>& flights, const std::string& label) {
  const RunResult* chosen = nullptr;
  for (const auto& flight : flights) {
    if (!label.empty() && flight.spec.label != label) continue;
    if (!label.empty() && !flight.completed())
      throw Error("optimality gap: the warm-start flight " + label + " did not complete (" +
                  status_text(flight.summary) + "): start from another");
    if (flight.completed() && (chosen == nullptr || flight.summary.cost < chosen->summary.cost)) chosen = &flight;
  }
  if (chosen == nullptr) {
    throw Error(label.empty() ? "optimality gap: no controller completed the horizon: nothing to warm start from"
                              : "optimality gap: the warm start " + label + " is none of the controllers flown");
  }
  return *chosen;
}

// The optimum as a run of the flight: its samples as log rows, its figures by the run metrics.
RunResult optimum_run(const Flight& flight, const OptimalControlProblem& problem, const OptimalControlSolution& solution,
                      const std::string& warm_start, const OptimalityOptions& options) {
  RunResult run;
  run.spec.label = run.spec.controller = "optimal";
  run.controller_origin = "Ipopt, multiple shooting (thetad optimal)";
  run.provenance = flight.provenance();
  YAML::Node& settings = run.settings;
  settings["transcription"] = "multiple shooting on the RK4 plant, input held over each control interval";
  settings["control_interval"] = options.control_interval;
  settings["intervals"] = problem.intervals;
  settings["derivatives"] = "exact: RK4 sensitivities with the plant's Jacobian (automatic differentiation); L-BFGS Hessian";
  settings["warm_start"] = warm_start;
  settings["ipopt_status"] = solution.outcome.status;
  settings["ipopt_iterations"] = solution.iterations;
  settings["ipopt_tolerance"] = options.solver.ipopt.tolerance;
  settings["max_defect"] = solution.constraint_violation;

  sim::RunSummary& summary = run.summary;
  summary.controller = "optimal";
  summary.settings = flight.settings();
  summary.settings.measure_compute_time = false;  // no control step to time
  summary.model_options = flight.model().options().to_string();
  summary.end_time = problem.horizon();
  if (!solution.outcome.converged) {
    summary.status = sim::RunStatus::failed;
    summary.reason = "Ipopt did not converge (" + solution.outcome.status + ")";
  }
  const double period = problem.controller_period();
  sim::RunMetrics metrics(problem.state_weights, problem.input_weights, period, problem.samples(), false);
  const auto columns = static_cast<Eigen::Index>(sim::log_schema().size());
  run.log.values.assign(static_cast<std::size_t>(problem.samples() * columns), 0.0);
  const Eigen::Index measured = column("meas_x_p_m"), command = column("cmd_T_mr_N"), applied = column("app_T_mr_N"),
                     rotor = column("Omega_mr_rad_per_s");
  for (Eigen::Index k = 0; k < solution.samples.rows(); ++k) {
    const double t = solution.samples(k, 0);
    const Eigen::VectorXd x = solution.samples.row(k).segment(1, kStateDim).transpose();
    const Eigen::VectorXd u = solution.samples.row(k).segment(1 + kStateDim, kInputDim).transpose();
    const Eigen::VectorXd v = solution.samples.row(k).tail(kStateDim).transpose();
    const Eigen::Vector3d reference = problem.reference->position(t);
    metrics.add(x.head<3>() - reference, v, u, 0);
    Eigen::Map<Eigen::RowVectorXd> row(run.log.values.data() + k * columns, columns);
    row(0) = t;
    row.segment<3>(1) = reference.transpose();
    row.segment(4, kStateDim) = x.transpose();
    row.segment(measured, kStateDim) = x.transpose();  // the transcription has no sensors
    row.segment(command, kInputDim) = u.transpose();
    row.segment(applied, kInputDim) = u.transpose();
    row(rotor) = flight.model().rotor_speed(x, u[heli::kTmr]);
  }
  metrics.finish(summary);
  return run;
}

}  // namespace

double OptimalityGap::gap_percent(const RunResult& flight) const {
  return 100.0 * (flight.summary.cost - optimum.summary.cost) / optimum.summary.cost;
}

OptimalityGap optimality_gap(const Flight& flight, std::vector<PreparedController>& controllers,
                             const OptimalityOptions& options, Progress* progress) {
  OptimalityGap gap;
  gap.problem = optimality_problem(flight, options);
  if (!options.warm_start.empty() &&
      std::none_of(controllers.begin(), controllers.end(),
                   [&](const PreparedController& c) { return c.spec.label == options.warm_start; })) {
    throw Error("optimality gap: the warm start " + options.warm_start + " is none of the controllers flown");
  }
  for (auto& controller : controllers) gap.flights.push_back(flight.fly(controller, progress));

  const RunResult& start = warm_start_flight(gap.flights, options.warm_start);
  gap.warm_start = start.spec.label;
  const sim::RunLog& log = start.log;
  Eigen::MatrixXd states(log.rows(), kStateDim), inputs(log.rows(), kInputDim);
  const Eigen::Index state = column("x_p_m"), command = column("cmd_T_mr_N");
  for (Eigen::Index k = 0; k < log.rows(); ++k) {
    states.row(k) = log.row(k).segment(state, kStateDim).transpose();
    inputs.row(k) = log.row(k).segment(command, kInputDim).transpose();
  }

  OptimalControlSettings solver = options.solver;
  if (progress) {
    progress->start("optimal (Ipopt from " + gap.warm_start + "):", solver.ipopt.max_iterations);
    solver.progress = [progress, outer = options.solver.progress](int iteration, double objective, double defect) {
      progress->update(iteration);
      if (outer) outer(iteration, objective, defect);
    };
  }
  const auto started = std::chrono::steady_clock::now();
  gap.solution = solve_optimal_control(gap.problem, shooting_guess(gap.problem, states, inputs), solver);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (progress) progress->finish(gap.solution.outcome.status + ", " + std::to_string(gap.solution.iterations) + " iterations");
  gap.optimum = optimum_run(flight, gap.problem, gap.solution, gap.warm_start, options);
  if (flight.settings().measure_compute_time) {
    gap.optimum.wall_seconds = wall;
    stamp_host_and_time(gap.optimum.provenance);
  }
  return gap;
}

}  // namespace thetad
