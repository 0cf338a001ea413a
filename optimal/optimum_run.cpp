#include "optimal/optimum_run.hpp"

#include "core/helicopter/state.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "core/sim/run_metrics.hpp"
#include "core/sim/simulator.hpp"
#include "optimal/shooting_interval.hpp"

namespace thetad {

namespace {

// How the transcription's derivatives were had: the helicopter's Jacobian is automatic
// differentiation, another plant's its own (SdcPlant::jacobian), or central differences without one.
const char* derivatives(const Flight& flight, const OptimalControlProblem& problem) {
  if (problem.finite_differences)
    return "RK4 sensitivities with central differences of f (the plant gives no Jacobian); L-BFGS Hessian";
  return flight.helicopter() ? "exact: RK4 sensitivities with the plant's Jacobian (automatic differentiation); "
                               "L-BFGS Hessian"
                             : "exact: RK4 sensitivities with the plant's Jacobian (SdcPlant::jacobian); L-BFGS Hessian";
}

}  // namespace

RunResult optimum_run(const Flight& flight, const OptimalControlProblem& problem, const OptimalControlSolution& solution,
                      const std::string& warm_start, double control_interval, double tolerance, const std::string& label) {
  RunResult run;
  run.spec.label = label;
  run.spec.controller = "optimal";
  run.controller_origin = "Ipopt, multiple shooting (thetad optimal)";
  run.provenance = flight.provenance();
  YAML::Node& settings = run.settings;
  settings["transcription"] = "multiple shooting on the RK4 plant, input held over each control interval";
  settings["cost"] = problem.deviation_trims ? "J_dev" : "J";
  settings["input_bounds"] = problem.bounded() ? "the actuators' magnitude limits (not their rates)" : "none";
  settings["start"] = problem.start_time();
  settings["control_interval"] = control_interval;
  settings["intervals"] = problem.intervals;
  settings["derivatives"] = derivatives(flight, problem);
  settings["warm_start"] = warm_start;
  settings["ipopt_status"] = solution.outcome.status;
  settings["ipopt_iterations"] = solution.iterations;
  settings["ipopt_tolerance"] = tolerance;
  settings["max_defect"] = solution.constraint_violation;

  sim::RunSummary& summary = run.summary;
  summary.controller = "optimal";
  summary.settings = flight.settings();
  summary.settings.measure_compute_time = false;  // no control step to time
  const SdcPlant& plant = flight.plant();
  const heli::Helicopter* helicopter = flight.helicopter();
  if (helicopter) summary.model_options = helicopter->options().to_string();
  summary.end_time = problem.start_time() + problem.horizon();
  if (!solution.outcome.converged) {
    summary.status = sim::RunStatus::failed;
    summary.reason = "Ipopt did not converge (" + solution.outcome.status + ")";
  }
  const double period = problem.controller_period();
  summary.tracked = plant.tracked_states();
  summary.inputs = plant.input_columns();
  const int n = plant.state_dim(), m = plant.input_dim();
  summary.saturation = sim::SaturationCounts::none(m);
  // J with the design weights and J_dev with its own, whichever the problem minimized: as every flight has them.
  const DesignDefaults design = plant.design_defaults();
  const auto tracked = static_cast<Eigen::Index>(summary.tracked.size());
  sim::RunMetrics metrics(design.state_weights, design.input_weights, tracked, period, problem.samples(), false);
  std::string no_deviation;
  std::optional<sim::DeviationCost> deviation = flight.deviation_cost(no_deviation);
  const std::vector<Reference> references = sampled_references(problem);
  run.log.columns = helicopter ? sim::helicopter_log_schema() : sim::log_schema(plant, *flight.make_disturbances());
  const auto columns = static_cast<Eigen::Index>(run.log.columns.size());
  run.log.values.assign(static_cast<std::size_t>(problem.samples() * columns), 0.0);
  const sim::LogLayout layout = sim::log_layout(plant);
  const std::vector<TrackedState> tracked_states = plant.tracked_states();
  Eigen::VectorXd error(tracked);
  const Eigen::Index rotor = helicopter ? sim::helicopter_log_column("Omega_mr_rad_per_s") : -1;
  for (Eigen::Index k = 0; k < solution.samples.rows(); ++k) {
    const double t = solution.samples(k, 0);
    const Eigen::VectorXd x = solution.samples.row(k).segment(1, n).transpose();
    const Eigen::VectorXd u = solution.samples.row(k).segment(1 + n, m).transpose();
    const Eigen::VectorXd v = solution.samples.row(k).tail(n).transpose();
    const Reference& reference = references[static_cast<std::size_t>(k)];
    for (Eigen::Index i = 0; i < tracked; ++i)
      error[i] = x[tracked_states[static_cast<std::size_t>(i)].index] - reference.position[i];
    metrics.add(error, v, u, 0);
    if (deviation) deviation->add(x, reference, v, u);
    Eigen::Map<Eigen::RowVectorXd> row(run.log.values.data() + k * columns, columns);
    row(0) = t;
    row.segment(1, tracked) = reference.position.head(tracked).transpose();
    row.segment(layout.state, n) = x.transpose();
    row.segment(layout.measured, n) = x.transpose();  // the transcription has no sensors
    row.segment(layout.command, m) = u.transpose();
    row.segment(layout.applied, m) = u.transpose();
    if (helicopter) row(rotor) = helicopter->rotor_speed(x, u[heli::kTmr]);
  }
  metrics.finish(summary);
  if (deviation) {
    summary.cost_dev = deviation->value();
    summary.cost_dev_weights = deviation->weights().name;
  } else {
    summary.cost_dev_weights = no_deviation;
  }
  return run;
}

}  // namespace thetad
