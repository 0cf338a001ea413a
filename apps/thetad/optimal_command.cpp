#include "apps/thetad/optimal_command.hpp"

#include <cstdio>

#include "apps/thetad/run_command.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/run_files.hpp"
#include "optimal/optimality_report.hpp"

namespace thetad::app {

CLI::App* add_optimal_command(CLI::App& app, OptimalArguments& arguments) {
  auto* optimal = app.add_subcommand(
      "optimal", "Each controller's cost (J_dev or J) over a horizon and its gap to the optimum of the same problem "
                 "(Ipopt, multiple shooting), flown ideal; write the optimal trajectory beside the flights. Exit code 0: "
                 "Ipopt converged, 3: it did not");
  optimal->add_option("--scenario", arguments.scenario, "Scenario file or the name of a shipped one")->required();
  optimal
      ->add_option("--cost", arguments.cost,
                   "The cost minimized and compared: j-dev (the comparison's score, docs/model.md §7.2) or j (Eq. 32)")
      ->capture_default_str()
      ->check(CLI::IsMember({"j-dev", "j"}));
  optimal
      ->add_option_function<std::string>(
          "--actuator-limits", [&arguments](const std::string& text) { arguments.actuator_limits = text == "on"; },
          "on: the flights have the servo limits (docs/model.md §12) and the optimum their magnitude bounds, solved "
          "bounded and then unbounded; off (default): neither")
      ->check(CLI::IsMember({"on", "off"}));
  optimal->add_option("--start", arguments.start,
                      "Seconds into the scenario where the segment starts, from each controller's state there (a whole "
                      "number of controller periods)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 86400.0));
  optimal->add_option("--horizon", arguments.horizon, "Seconds of the segment (a whole number of control intervals)")
      ->required()
      ->check(CLI::Range(1e-6, 86400.0));
  optimal->add_option("--control-interval", arguments.control_interval,
                      "Seconds the optimal input is held (a whole number of controller periods)")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 86400.0));
  optimal->add_option("--controllers", arguments.controllers, "Comma-separated NAME, LABEL=NAME or LABEL=NAME:SETTINGS.yaml, or all (every registered controller but the examples)")
      ->delimiter(',')
      ->capture_default_str();
  optimal->add_option("--settings", arguments.settings, "Controller settings (YAML): a map from controller name to its settings block");
  optimal->add_option("--warm-start", arguments.warm_start,
                      "The label of the flight Ipopt starts from (default: the cheapest that completed)");
  optimal->add_option("--max-iterations", arguments.max_iterations, "Ipopt's iteration limit")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  optimal->add_option("--tolerance", arguments.tolerance, "Ipopt's convergence tolerance (tol)")
      ->capture_default_str()
      ->check(CLI::Range(1e-14, 1.0));
  optimal->add_flag("--no-timing", arguments.no_timing, "Measure no wall-clock time: reruns give byte-identical files");
  optimal->add_flag("--quiet", arguments.quiet, "No progress display");
  optimal->add_option("--out", arguments.out, "Output directory (created; checked before anything flies)")->required();
  return optimal;
}

namespace {

void print_gaps(const Flight& flight, const OptimalityGap& gap, const OptimalityOptions& options) {
  const OptimalControlProblem& first = gap.optima.front().problem;
  const std::string cost = cost_name(gap.cost), best = cost + "*";
  std::printf("%s, %g s from t = %g s (ideal%s; %s of every controller sample, docs/optimality.md)\n",
              flight.scenario().name.c_str(), first.horizon(), first.start_time(),
              first.bounded() ? ", actuator limits; the optimum bounded by their magnitudes" : "", cost.c_str());
  for (const SegmentOptimum& optimum : gap.optima) {
    for (const SolvedOptimum* solved : {&optimum.optimum, optimum.unbounded ? &*optimum.unbounded : nullptr}) {
      if (solved == nullptr) continue;
      std::printf("%s: Ipopt %s after %d iterations from %s; input held %g s (%d intervals); largest defect %.2g\n",
                  solved->run.spec.label.c_str(), solved->solution.outcome.status.c_str(), solved->solution.iterations,
                  solved->run.settings["warm_start"].as<std::string>().c_str(), options.control_interval,
                  optimum.problem.intervals, solved->solution.constraint_violation);
    }
  }
  const bool bounded = first.bounded();
  std::printf("%-16s %-22s %16s %16s %12s", "label", "status", cost.c_str(), best.c_str(), "gap (%)");
  if (bounded) std::printf(" %16s %14s", (best + " unbounded").c_str(), "gap unb. (%)");
  std::printf("\n");
  for (std::size_t i = 0; i < gap.flights.size(); ++i) {
    const SegmentOptimum* optimum = gap.optimum_for(i);
    char value[32] = "-", optimal[32] = "-", percent[32] = "-", unbounded[32] = "-", unbounded_percent[32] = "-";
    if (optimum != nullptr) {
      std::snprintf(value, sizeof value, "%.8g", gap.costs[i]);
      std::snprintf(optimal, sizeof optimal, "%.8g", optimum->cost(gap.cost));
      std::snprintf(percent, sizeof percent, "%.4f", gap.gap_percent(i));
      std::snprintf(unbounded, sizeof unbounded, "%.8g", optimum->unbounded_cost(gap.cost));
      std::snprintf(unbounded_percent, sizeof unbounded_percent, "%.4f", gap.unbounded_gap_percent(i));
    }
    std::printf("%-16s %-22s %16s %16s %12s", gap.flights[i].spec.label.c_str(),
                status_text(gap.flights[i].summary).c_str(), value, optimal, percent);
    if (bounded) std::printf(" %16s %14s", unbounded, unbounded_percent);
    std::printf("\n");
  }
  if (bounded && !unbounded_at_most_bounded(gap)) {
    std::printf("warning: an unbounded optimum costs more than its bounded one: a solve stopped short of its minimum "
                "(raise --max-iterations or tighten --tolerance)\n");
  }
}

}  // namespace

int run_optimal(const OptimalArguments& arguments) {
  RunControls controls;
  controls.duration = arguments.start + arguments.horizon;
  controls.ideal = true;  // the optimum is that of the nominal plant with ideal sensors
  controls.actuator_limits = arguments.actuator_limits;
  controls.log_every = 1;
  controls.summary_only = false;
  if (arguments.no_timing) controls.timing = false;
  const Flight flight(arguments.scenario, controls);
  OptimalityOptions options;
  options.cost = arguments.cost == "j" ? OptimalCost::paper : OptimalCost::deviation;
  options.control_interval = arguments.control_interval;
  options.start = arguments.start;
  options.warm_start = arguments.warm_start;
  options.solver.ipopt.max_iterations = arguments.max_iterations;
  options.solver.ipopt.tolerance = arguments.tolerance;
  // A horizon or interval off the grid fails before the controllers are built.
  if (optimality_problem(flight, options).finite_differences)
    std::fprintf(stderr, "warning: the plant %s gives no Jacobian (SdcPlant::jacobian): the optimum's derivatives are "
                         "central differences of f, slower and exact to about 1e-10 relative only\n",
                 flight.provenance().plant.c_str());
  std::vector<PreparedController> controllers;
  for (const auto& spec : parse_controller_specs(arguments.controllers, arguments.settings))
    controllers.push_back(flight.prepare(spec));
  prepare_output_folder(arguments.out);

  Progress progress(Progress::mode_for_stderr(arguments.quiet));
  const OptimalityGap gap = optimality_gap(flight, controllers, options, &progress);
  write_optimality(flight, gap, options, arguments.out);
  print_gaps(flight, gap, options);
  std::printf("Wrote %s, %s and the result files of each controller and optimum in %s.\n",
              (arguments.out / "optimality.json").c_str(), (arguments.out / "comparison.json").c_str(),
              arguments.out.c_str());
  return optimality_converged(gap) && unbounded_at_most_bounded(gap) ? kExitCompleted : kExitDiverged;
}

}  // namespace thetad::app
