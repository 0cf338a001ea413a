#include "apps/thetad/optimal_command.hpp"

#include <cstdio>

#include "apps/thetad/run_command.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "experiment/comparison.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/run_files.hpp"
#include "optimal/optimality_gap.hpp"

namespace thetad::app {

CLI::App* add_optimal_command(CLI::App& app, OptimalArguments& arguments) {
  auto* optimal = app.add_subcommand(
      "optimal", "Each controller's cost J over a horizon and its gap to the optimum of the same problem (Ipopt, "
                 "multiple shooting), flown ideal; write the optimal trajectory beside the flights. Exit code 0: "
                 "Ipopt converged, 3: it did not");
  optimal->add_option("--scenario", arguments.scenario, "Scenario file or the name of a shipped one")->required();
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
  optimal->add_option("--controllers", arguments.controllers, "Comma-separated NAME, LABEL=NAME or LABEL=NAME:SETTINGS.yaml")
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

int run_optimal(const OptimalArguments& arguments) {
  RunControls controls;
  controls.duration = arguments.start + arguments.horizon;
  controls.ideal = true;  // the optimum is that of the nominal plant with ideal servos
  controls.log_every = 1;
  controls.summary_only = false;
  if (arguments.no_timing) controls.timing = false;
  const Flight flight(arguments.scenario, controls);
  OptimalityOptions options;
  options.control_interval = arguments.control_interval;
  options.start = arguments.start;
  options.warm_start = arguments.warm_start;
  options.solver.ipopt.max_iterations = arguments.max_iterations;
  options.solver.ipopt.tolerance = arguments.tolerance;
  optimality_problem(flight, options);  // a horizon or interval off the grid fails before the controllers are built
  std::vector<PreparedController> controllers;
  for (const auto& spec : parse_controller_specs(arguments.controllers, arguments.settings))
    controllers.push_back(flight.prepare(spec));
  for (const auto& controller : controllers) {
    if (controller.spec.label.starts_with("optimal"))
      throw Error("thetad optimal: labels starting 'optimal' name the optima; label the controller otherwise");
  }
  prepare_output_folder(arguments.out);
  const auto comparison_file = arguments.out / "comparison.json", optimality_file = arguments.out / "optimality.json";
  for (const auto& stale : {comparison_file, optimality_file}) {
    std::error_code error;
    std::filesystem::remove(stale, error);
    if (error) throw Error("cannot remove the old " + stale.string() + ": " + error.message());
  }

  Progress progress(Progress::mode_for_stderr(arguments.quiet));
  OptimalityGap gap = optimality_gap(flight, controllers, options, &progress);

  std::vector<RunResult> runs = gap.flights;
  for (const auto& optimum : gap.optima) runs.push_back(optimum.run);
  std::vector<RunFiles> files;
  for (const auto& run : runs) files.push_back(write_run_files(run, arguments.out));

  const double start = gap.optima.front().problem.start_time(), horizon = gap.optima.front().problem.horizon();
  std::printf("%s, %g s from t = %g s (ideal; J of every controller sample, docs/optimality.md)\n",
              flight.scenario().name.c_str(), horizon, start);
  bool converged = true;
  nlohmann::ordered_json optima = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < gap.optima.size(); ++i) {
    const SegmentOptimum& optimum = gap.optima[i];
    const OptimalControlSolution& solution = optimum.solution;
    converged = converged && solution.outcome.converged;
    std::printf("%s: Ipopt %s after %d iterations from %s's flight; input held %g s (%d intervals); largest defect %.2g\n",
                optimum.run.spec.label.c_str(), solution.outcome.status.c_str(), solution.iterations, optimum.from.c_str(),
                arguments.control_interval, optimum.problem.intervals, solution.constraint_violation);
    optima.push_back({{"label", optimum.run.spec.label},
                      {"from", optimum.from},
                      {"ipopt_status", solution.outcome.status},
                      {"ipopt_converged", solution.outcome.converged},
                      {"ipopt_iterations", solution.iterations},
                      {"max_defect", solution.constraint_violation},
                      {"optimal_cost", optimum.run.summary.cost},
                      {"result", files[gap.flights.size() + i].json.filename().string()}});
  }
  std::printf("%-16s %-22s %16s %16s %12s\n", "label", "status", "J", "J*", "gap (%)");
  nlohmann::ordered_json gaps = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < gap.flights.size(); ++i) {
    const RunResult& flight_run = gap.flights[i];
    const SegmentOptimum* optimum = gap.optimum_for(i);
    char cost[32] = "-", best[32] = "-", percent[32] = "-";
    if (optimum != nullptr) {
      std::snprintf(cost, sizeof cost, "%.8g", gap.costs[i]);
      std::snprintf(best, sizeof best, "%.8g", optimum->run.summary.cost);
      std::snprintf(percent, sizeof percent, "%.4f", gap.gap_percent(i));
    }
    std::printf("%-16s %-22s %16s %16s %12s\n", flight_run.spec.label.c_str(), status_text(flight_run.summary).c_str(),
                cost, best, percent);
    const auto number_or_null = [&](double value) {
      return optimum != nullptr ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
    };
    gaps.push_back({{"label", flight_run.spec.label},
                    {"controller", flight_run.spec.controller},
                    {"status", status_text(flight_run.summary)},
                    {"cost", number_or_null(gap.costs[i])},
                    {"optimum", optimum != nullptr ? nlohmann::ordered_json(optimum->run.spec.label) : nullptr},
                    {"optimal_cost", number_or_null(optimum != nullptr ? optimum->run.summary.cost : 0.0)},
                    {"gap_percent", number_or_null(gap.gap_percent(i))}});
  }

  write_file_atomically(comparison_file, comparison_json(flight, runs, files).dump(2) + "\n");
  nlohmann::ordered_json result = {{"format", "thetad-optimality-2"},
                                   {"scenario", flight.scenario().name},
                                   {"start_s", start},
                                   {"horizon_s", horizon},
                                   {"control_interval_s", arguments.control_interval},
                                   {"intervals", gap.optima.front().problem.intervals},
                                   {"optima", optima},
                                   {"controllers", gaps},
                                   {"provenance", to_json(gap.optima.front().run.provenance)}};
  write_file_atomically(optimality_file, result.dump(2) + "\n");
  std::printf("Wrote %s, %s and the result files of each controller and optimum in %s.\n", optimality_file.c_str(),
              comparison_file.c_str(), arguments.out.c_str());
  return converged ? kExitCompleted : kExitDiverged;
}

}  // namespace thetad::app
