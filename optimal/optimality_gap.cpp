#include "optimal/optimality_gap.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "core/sim/simulator.hpp"
#include "optimal/optimum_run.hpp"
#include "optimal/shooting_interval.hpp"

namespace thetad {

const char* cost_name(OptimalCost cost) { return cost == OptimalCost::deviation ? "J_dev" : "J"; }

namespace {

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
                "); the optimum is that of the nominal plant: fly it ideal (actuator limits may stay on)");
  }
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
  const SdcPlant& plant = flight.plant();
  const DesignDefaults design = plant.design_defaults();
  OptimalControlProblem problem;
  problem.plant = &plant;
  problem.reference = &flight.scenario().trajectory;
  problem.initial_state = flight.initial_state();
  problem.first_sample = first;
  problem.state_weights = design.state_weights;
  problem.input_weights = design.input_weights;
  problem.dt = s.dt;
  problem.controller_period_steps = s.controller_period_steps;
  problem.interval_periods = interval_periods;
  problem.intervals = samples / interval_periods;
  if (flight.helicopter()) problem.sampled_position_integral = heli::kXi;  // as simulate() prices J
  Eigen::MatrixXd dfdx(plant.state_dim(), plant.state_dim()), dfdu(plant.state_dim(), plant.input_dim());
  problem.finite_differences = !plant.jacobian(flight.initial_state(), design.input, dfdx, dfdu);
  if (s.actuator_limits.enabled) {
    problem.input_lower = s.actuator_limits.lower;
    problem.input_upper = s.actuator_limits.upper;
  }
  if (options.cost == OptimalCost::deviation) {
    std::string why_not;
    const std::optional<sim::DeviationCost> deviation = flight.deviation_cost(why_not);
    if (!deviation) throw Error("optimality gap: this flight has no J_dev (" + why_not + "); compare on J instead");
    problem.state_weights = deviation->weights().state;
    problem.input_weights = deviation->weights().input;
    problem.deviation_trims = deviation->trims();
  }
  problem.validate();
  return problem;
}

namespace {

// A completed flight's cost over its whole run: J_dev or J.
double flight_cost(const RunResult& run, OptimalCost cost) {
  if (cost == OptimalCost::paper) return run.summary.cost;
  return run.summary.cost_dev.value_or(std::numeric_limits<double>::quiet_NaN());
}

const RunResult& warm_start_flight(const std::vector<RunResult>& flights, const std::string& label, OptimalCost cost) {
  const RunResult* chosen = nullptr;
  for (const auto& flight : flights) {
    if (!label.empty() && flight.spec.label != label) continue;
    if (!label.empty() && !flight.completed())
      throw Error("optimality gap: the warm-start flight " + label + " did not complete (" +
                  status_text(flight.summary) + "): start from another");
    if (flight.completed() && (chosen == nullptr || flight_cost(flight, cost) < flight_cost(*chosen, cost))) chosen = &flight;
  }
  if (chosen == nullptr) {
    throw Error(label.empty() ? "optimality gap: no controller completed the horizon: nothing to warm start from"
                              : "optimality gap: the warm start " + label + " is none of the controllers flown");
  }
  return *chosen;
}

// The states, commands and applied inputs of a logged flight, one row per controller sample: the
// commands are what its cost priced, the applied inputs what moved it (within the limits).
struct Logged {
  Eigen::MatrixXd states, commands, applied;

  Logged(const RunResult& run, const SdcPlant& plant)
      : states(run.log.rows(), plant.state_dim()),
        commands(run.log.rows(), plant.input_dim()),
        applied(run.log.rows(), plant.input_dim()) {
    const sim::LogLayout layout = sim::log_layout(plant);
    for (Eigen::Index k = 0; k < run.log.rows(); ++k) {
      states.row(k) = run.log.row(k).segment(layout.state, states.cols());
      commands.row(k) = run.log.row(k).segment(layout.command, commands.cols());
      applied.row(k) = run.log.row(k).segment(layout.applied, applied.cols());
    }
  }
  // From the segment's first sample on.
  static Eigen::MatrixXd from(const Eigen::MatrixXd& rows, int first) { return rows.bottomRows(rows.rows() - first); }
};

// The segment from the flight's state at its start: that state, and the sampled integral of the
// position error there (the left-rectangle sum simulate() keeps).
OptimalControlProblem from_flight(const OptimalControlProblem& segment, const Logged& flight) {
  OptimalControlProblem problem = segment;
  const double period = segment.controller_period();
  PositionIntegral error;
  for (int k = 0; segment.sampled_position_integral && k < segment.first_sample; ++k) {
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
      shooting_guess(samples, Logged::from(flight.states, problem.first_sample),
                     Logged::from(flight.commands, problem.first_sample));
  ShootingInterval interval(samples);
  Eigen::VectorXd next(samples.node_dim());
  double cost = 0.0;
  for (int k = 0; k < samples.intervals; ++k)
    cost += interval.propagate(k, nodes.nodes.row(k).transpose(), nodes.inputs.row(k).transpose(), next);
  return cost;
}

// One solve from `start`, with a progress display, as a run labelled `label`.
SolvedOptimum solve(const Flight& flight, const OptimalControlProblem& problem, const ShootingTrajectory& start,
                    const std::string& from, const OptimalityOptions& options, Progress* progress,
                    const std::string& label) {
  OptimalControlSettings solver = options.solver;
  if (progress) {
    progress->start(label + " (Ipopt from " + from + "):", solver.ipopt.max_iterations, "Ipopt iterations at most");
    solver.progress = [progress, outer = options.solver.progress](int iteration, double objective, double defect) {
      progress->update(iteration);
      if (outer) outer(iteration, objective, defect);
    };
  }
  const auto started = std::chrono::steady_clock::now();
  SolvedOptimum solved;
  solved.solution = solve_optimal_control(problem, start, solver);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (progress)
    progress->finish(solved.solution.outcome.status + ", " + std::to_string(solved.solution.iterations) + " iterations");
  solved.run = optimum_run(flight, problem, solved.solution, from, options.control_interval,
                           options.solver.ipopt.tolerance, label);
  if (flight.settings().measure_compute_time) {
    solved.run.wall_time_s = wall;
    stamp_host_and_time(solved.run.provenance);
  }
  return solved;
}

// From the flight `from` (its applied inputs, within any bounds); with bounds, then without them
// from the bounded optimum, so that the unbounded solve starts where the bounded one ended.
SegmentOptimum solve_segment(const Flight& flight, const OptimalControlProblem& segment, const RunResult& from,
                             const OptimalityOptions& options, Progress* progress, const std::string& suffix) {
  SegmentOptimum optimum;
  optimum.from = from.spec.label;
  const Logged log(from, flight.plant());
  const int first = segment.first_sample;
  optimum.problem = first == 0 ? segment : from_flight(segment, log);
  const ShootingTrajectory start =
      shooting_guess(optimum.problem, Logged::from(log.states, first), Logged::from(log.applied, first));
  optimum.optimum = solve(flight, optimum.problem, start, optimum.from, options, progress, "optimal" + suffix);
  if (optimum.problem.bounded()) {
    OptimalControlProblem unbounded = optimum.problem;
    unbounded.input_lower.resize(0);
    unbounded.input_upper.resize(0);
    optimum.unbounded = solve(flight, unbounded, optimum.optimum.solution.shooting, optimum.optimum.run.spec.label,
                              options, progress, "optimal-unbounded" + suffix);
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

double SegmentOptimum::cost(OptimalCost kind) const { return flight_cost(optimum.run, kind); }

double SegmentOptimum::unbounded_cost(OptimalCost kind) const {
  return unbounded ? flight_cost(unbounded->run, kind) : std::numeric_limits<double>::quiet_NaN();
}

double OptimalityGap::gap_percent(std::size_t i) const {
  const SegmentOptimum* optimum = optimum_for(i);
  if (optimum == nullptr) return std::numeric_limits<double>::quiet_NaN();
  const double best = optimum->cost(cost);
  return 100.0 * (costs.at(i) - best) / best;
}

double OptimalityGap::unbounded_gap_percent(std::size_t i) const {
  const SegmentOptimum* optimum = optimum_for(i);
  if (optimum == nullptr) return std::numeric_limits<double>::quiet_NaN();
  const double best = optimum->unbounded_cost(cost);
  return 100.0 * (costs.at(i) - best) / best;
}

OptimalityGap optimality_gap(const Flight& flight, std::vector<PreparedController>& controllers,
                             const OptimalityOptions& options, Progress* progress) {
  OptimalityGap gap;
  gap.cost = options.cost;
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
  for (const auto& controller : controllers) {
    if (controller.spec.label.starts_with("optimal"))
      throw Error("optimality gap: labels starting 'optimal' name the optima; label the controller '" +
                  controller.spec.label + "' otherwise");
  }
  for (auto& controller : controllers) gap.flights.push_back(flight.fly(controller, progress));

  for (const auto& run : gap.flights) {
    if (!run.completed())
      gap.costs.push_back(std::numeric_limits<double>::quiet_NaN());
    else if (segment.first_sample == 0)
      gap.costs.push_back(flight_cost(run, options.cost));
    else {
      const Logged log(run, flight.plant());
      gap.costs.push_back(segment_cost(from_flight(segment, log), log));
    }
  }
  if (segment.first_sample == 0) {
    const RunResult& start = warm_start_flight(gap.flights, options.warm_start, options.cost);
    gap.optima.push_back(solve_segment(flight, segment, start, options, progress, ""));
    return gap;
  }
  for (const auto& run : gap.flights) {
    if (run.completed())
      gap.optima.push_back(solve_segment(flight, segment, run, options, progress, "-from-" + run.spec.label));
  }
  if (gap.optima.empty()) throw Error("optimality gap: no controller completed the flight: no state to start the segment from");
  return gap;
}

}  // namespace thetad
