#include "optimal/optimality_gap.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "core/sim/run_metrics.hpp"
#include "optimal/shooting_interval.hpp"

namespace thetad {

namespace {

using heli::kInputDim;
using heli::kStateDim;

Eigen::Index column(const std::string& header) {
  const auto& schema = sim::helicopter_log_schema();
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
  if (!(options.start >= 0.0)) throw Error("optimality gap: the start (" + std::to_string(options.start) + " s) is negative");
  const int first = options.start == 0.0 ? 0 : periods_in(options.start, period, "start");
  const int samples = periods_in(s.duration, period, "flight") - first;
  if (samples < 1) {
    throw Error("optimality gap: the start (" + std::to_string(options.start) + " s) leaves nothing of the " +
                std::to_string(s.duration) + " s flight");
  }
  if (samples % interval_periods != 0) {
    throw Error("optimality gap: the horizon (" + std::to_string(samples * period) +
                " s) is not a whole number of control intervals (" + std::to_string(options.control_interval) + " s)");
  }
  const DesignDefaults design = flight.model().design_defaults();
  OptimalControlProblem problem;
  problem.plant = &flight.model();
  problem.reference = &flight.scenario().trajectory;
  problem.initial_state = flight.initial_state();
  problem.first_sample = first;
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
                      const std::string& warm_start, const OptimalityOptions& options, const std::string& label) {
  RunResult run;
  run.spec.label = label;
  run.spec.controller = "optimal";
  run.controller_origin = "Ipopt, multiple shooting (thetad optimal)";
  run.provenance = flight.provenance();
  YAML::Node& settings = run.settings;
  settings["transcription"] = "multiple shooting on the RK4 plant, input held over each control interval";
  settings["start"] = problem.start_time();
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
  summary.end_time = problem.start_time() + problem.horizon();
  if (!solution.outcome.converged) {
    summary.status = sim::RunStatus::failed;
    summary.reason = "Ipopt did not converge (" + solution.outcome.status + ")";
  }
  const double period = problem.controller_period();
  summary.tracked = flight.model().tracked_states();
  summary.inputs = flight.model().input_columns();
  summary.saturation = sim::SaturationCounts::none(kInputDim);
  sim::RunMetrics metrics(problem.state_weights, problem.input_weights, 3, period, problem.samples(), false);
  run.log.columns = sim::helicopter_log_schema();
  const auto columns = static_cast<Eigen::Index>(run.log.columns.size());
  run.log.values.assign(static_cast<std::size_t>(problem.samples() * columns), 0.0);
  const Eigen::Index measured = column("meas_x_p_m"), command = column("cmd_T_mr_N"), applied = column("app_T_mr_N"),
                     rotor = column("Omega_mr_rad_per_s");
  for (Eigen::Index k = 0; k < solution.samples.rows(); ++k) {
    const double t = solution.samples(k, 0);
    const Eigen::VectorXd x = solution.samples.row(k).segment(1, kStateDim).transpose();
    const Eigen::VectorXd u = solution.samples.row(k).segment(1 + kStateDim, kInputDim).transpose();
    const Eigen::VectorXd v = solution.samples.row(k).tail(kStateDim).transpose();
    const Eigen::Vector3d reference = problem.reference->position(t);
    metrics.add(Eigen::VectorXd(x.head<3>() - reference), v, u, 0);
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

// The states and commands of a logged flight, one row per controller sample.
struct Logged {
  Eigen::MatrixXd states, inputs;

  explicit Logged(const RunResult& run) : states(run.log.rows(), kStateDim), inputs(run.log.rows(), kInputDim) {
    const Eigen::Index state = column("x_p_m"), command = column("cmd_T_mr_N");
    for (Eigen::Index k = 0; k < run.log.rows(); ++k) {
      states.row(k) = run.log.row(k).segment(state, kStateDim);
      inputs.row(k) = run.log.row(k).segment(command, kInputDim);
    }
  }
  // From the segment's first sample on.
  Eigen::MatrixXd states_from(int first) const { return states.bottomRows(states.rows() - first); }
  Eigen::MatrixXd inputs_from(int first) const { return inputs.bottomRows(inputs.rows() - first); }
};

// The segment from the flight's state at its start: that state, and the sampled integral of the
// position error there (the left-rectangle sum simulate() keeps).
OptimalControlProblem from_flight(const OptimalControlProblem& segment, const Logged& flight) {
  OptimalControlProblem problem = segment;
  const double period = segment.controller_period();
  PositionIntegral error;
  for (int k = 0; k < segment.first_sample; ++k) {
    const Eigen::Vector3d position = flight.states.row(k).head<3>().transpose();
    error.accumulate(position - segment.reference->position(k * period), period);
  }
  problem.initial_state = flight.states.row(segment.first_sample).transpose();
  problem.initial_integral = error.value;
  return problem;
}

// The flight's J over the segment, priced sample by sample as simulate() priced it.
double segment_cost(const OptimalControlProblem& problem, const Logged& flight) {
  OptimalControlProblem samples = problem;
  samples.interval_periods = 1;
  samples.intervals = problem.samples();
  const ShootingTrajectory nodes =
      shooting_guess(samples, flight.states_from(problem.first_sample), flight.inputs_from(problem.first_sample));
  ShootingInterval interval(samples);
  Eigen::VectorXd next(samples.node_dim());
  double cost = 0.0;
  for (int k = 0; k < samples.intervals; ++k)
    cost += interval.propagate(k, nodes.nodes.row(k).transpose(), nodes.inputs.row(k).transpose(), next);
  return cost;
}

SegmentOptimum solve_segment(const Flight& flight, const OptimalControlProblem& segment, const RunResult& from,
                             const OptimalityOptions& options, Progress* progress, const std::string& label) {
  SegmentOptimum optimum;
  optimum.from = from.spec.label;
  const Logged log(from);
  const int first = segment.first_sample;
  optimum.problem = first == 0 ? segment : from_flight(segment, log);
  OptimalControlSettings solver = options.solver;
  if (progress) {
    progress->start(label + " (Ipopt from " + optimum.from + "):", solver.ipopt.max_iterations, "Ipopt iterations at most");
    solver.progress = [progress, outer = options.solver.progress](int iteration, double objective, double defect) {
      progress->update(iteration);
      if (outer) outer(iteration, objective, defect);
    };
  }
  const auto started = std::chrono::steady_clock::now();
  optimum.solution = solve_optimal_control(
      optimum.problem, shooting_guess(optimum.problem, log.states_from(first), log.inputs_from(first)), solver);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (progress)
    progress->finish(optimum.solution.outcome.status + ", " + std::to_string(optimum.solution.iterations) + " iterations");
  optimum.run = optimum_run(flight, optimum.problem, optimum.solution, optimum.from, options, label);
  if (flight.settings().measure_compute_time) {
    optimum.run.wall_seconds = wall;
    stamp_host_and_time(optimum.run.provenance);
  }
  return optimum;
}

}  // namespace

const SegmentOptimum* OptimalityGap::optimum_for(std::size_t i) const {
  if (!flights.at(i).completed()) return nullptr;
  for (const auto& optimum : optima) {
    if (optimum.problem.first_sample == 0 || optimum.from == flights[i].spec.label) return &optimum;
  }
  return nullptr;
}

double OptimalityGap::gap_percent(std::size_t i) const {
  const SegmentOptimum* optimum = optimum_for(i);
  if (optimum == nullptr) return std::numeric_limits<double>::quiet_NaN();
  const double best = optimum->run.summary.cost;
  return 100.0 * (costs.at(i) - best) / best;
}

OptimalityGap optimality_gap(const Flight& flight, std::vector<PreparedController>& controllers,
                             const OptimalityOptions& options, Progress* progress) {
  OptimalityGap gap;
  const OptimalControlProblem segment = optimality_problem(flight, options);
  if (!options.warm_start.empty() && segment.first_sample > 0) {
    throw Error("optimality gap: a warm start applies to a segment from t = 0; from mid-flight each completed flight "
                "starts its own optimum");
  }
  if (!options.warm_start.empty() &&
      std::none_of(controllers.begin(), controllers.end(),
                   [&](const PreparedController& c) { return c.spec.label == options.warm_start; })) {
    throw Error("optimality gap: the warm start " + options.warm_start + " is none of the controllers flown");
  }
  for (auto& controller : controllers) gap.flights.push_back(flight.fly(controller, progress));

  for (const auto& run : gap.flights) {
    if (!run.completed())
      gap.costs.push_back(std::numeric_limits<double>::quiet_NaN());
    else if (segment.first_sample == 0)
      gap.costs.push_back(run.summary.cost);
    else
      gap.costs.push_back(segment_cost(from_flight(segment, Logged(run)), Logged(run)));
  }
  if (segment.first_sample == 0) {
    const RunResult& start = warm_start_flight(gap.flights, options.warm_start);
    gap.optima.push_back(solve_segment(flight, segment, start, options, progress, "optimal"));
    return gap;
  }
  for (const auto& run : gap.flights) {
    if (run.completed())
      gap.optima.push_back(solve_segment(flight, segment, run, options, progress, "optimal-from-" + run.spec.label));
  }
  if (gap.optima.empty()) throw Error("optimality gap: no controller completed the flight: no state to start the segment from");
  return gap;
}

}  // namespace thetad
