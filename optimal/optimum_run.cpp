#include "optimal/optimum_run.hpp"

#include "core/helicopter/state.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "core/sim/run_metrics.hpp"
#include "optimal/shooting_interval.hpp"

namespace thetad {

using heli::kInputDim;
using heli::kStateDim;

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
  settings["derivatives"] = "exact: RK4 sensitivities with the plant's Jacobian (automatic differentiation); L-BFGS Hessian";
  settings["warm_start"] = warm_start;
  settings["ipopt_status"] = solution.outcome.status;
  settings["ipopt_iterations"] = solution.iterations;
  settings["ipopt_tolerance"] = tolerance;
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
  // J with the design weights and J_dev with its own, whichever the problem minimized: as every flight has them.
  const DesignDefaults design = flight.model().design_defaults();
  sim::RunMetrics metrics(design.state_weights, design.input_weights, 3, period, problem.samples(), false);
  std::string no_deviation;
  std::optional<sim::DeviationCost> deviation = flight.deviation_cost(no_deviation);
  const std::vector<Reference> references = sampled_references(problem);
  run.log.columns = sim::helicopter_log_schema();
  const auto columns = static_cast<Eigen::Index>(run.log.columns.size());
  run.log.values.assign(static_cast<std::size_t>(problem.samples() * columns), 0.0);
  const Eigen::Index measured = sim::helicopter_log_column("meas_x_p_m"),
                     command = sim::helicopter_log_column("cmd_T_mr_N"),
                     applied = sim::helicopter_log_column("app_T_mr_N"),
                     rotor = sim::helicopter_log_column("Omega_mr_rad_per_s");
  for (Eigen::Index k = 0; k < solution.samples.rows(); ++k) {
    const double t = solution.samples(k, 0);
    const Eigen::VectorXd x = solution.samples.row(k).segment(1, kStateDim).transpose();
    const Eigen::VectorXd u = solution.samples.row(k).segment(1 + kStateDim, kInputDim).transpose();
    const Eigen::VectorXd v = solution.samples.row(k).tail(kStateDim).transpose();
    const Reference& reference = references[static_cast<std::size_t>(k)];
    metrics.add(Eigen::VectorXd(x.head<3>() - reference.position), v, u, 0);
    if (deviation) deviation->add(x, reference, v, u);
    Eigen::Map<Eigen::RowVectorXd> row(run.log.values.data() + k * columns, columns);
    row(0) = t;
    row.segment<3>(1) = reference.position.transpose();
    row.segment(4, kStateDim) = x.transpose();
    row.segment(measured, kStateDim) = x.transpose();  // the transcription has no sensors
    row.segment(command, kInputDim) = u.transpose();
    row.segment(applied, kInputDim) = u.transpose();
    row(rotor) = flight.model().rotor_speed(x, u[heli::kTmr]);
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
