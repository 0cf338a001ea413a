#include "optimal/optimality_report.hpp"

#include <cmath>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "experiment/comparison.hpp"
#include "experiment/provenance.hpp"

namespace thetad {

namespace {

nlohmann::ordered_json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json solve_json(const SolvedOptimum& solved, const RunFiles* files) {
  const OptimalControlSolution& solution = solved.solution;
  nlohmann::ordered_json solve = {{"label", solved.run.spec.label},
          {"ipopt_status", solution.outcome.status},
          {"ipopt_converged", solution.outcome.converged},
          {"ipopt_iterations", solution.iterations},
          {"max_defect", solution.constraint_violation},
          {"cost", solved.run.summary.cost},
          {"cost_dev", number_or_null(solved.run.summary.cost_dev.value_or(NAN))}};
  if (files) solve["result"] = files->json.filename().string();
  return solve;
}

}  // namespace

std::vector<RunResult> optimality_runs(const OptimalityGap& gap) {
  std::vector<RunResult> runs = gap.flights;
  for (const auto& optimum : gap.optima) {
    runs.push_back(optimum.optimum.run);
    if (optimum.unbounded) runs.push_back(optimum.unbounded->run);
  }
  return runs;
}

bool optimality_converged(const OptimalityGap& gap) {
  for (const auto& optimum : gap.optima) {
    if (!optimum.optimum.solution.outcome.converged) return false;
    if (optimum.unbounded && !optimum.unbounded->solution.outcome.converged) return false;
  }
  return true;
}

bool unbounded_at_most_bounded(const OptimalityGap& gap, double relative) {
  for (const auto& optimum : gap.optima) {
    if (!optimum.unbounded) continue;
    const double bounded = optimum.cost(gap.cost), unbounded = optimum.unbounded_cost(gap.cost);
    if (!(unbounded <= bounded + relative * std::abs(bounded))) return false;
  }
  return true;
}

nlohmann::ordered_json optimality_json(const Flight& flight, const OptimalityGap& gap, const OptimalityOptions& options,
                                       const std::vector<RunFiles>& files) {
  const OptimalControlProblem& first = gap.optima.front().problem;
  const std::string cost = cost_name(gap.cost);
  nlohmann::ordered_json optima = nlohmann::ordered_json::array();
  std::size_t file = gap.flights.size();
  const auto next_files = [&files, &file]() { return files.empty() ? nullptr : &files.at(file++); };
  for (const auto& optimum : gap.optima) {
    nlohmann::ordered_json entry = {{"from", optimum.from}, {"intervals", optimum.problem.intervals}};
    entry["optimum"] = solve_json(optimum.optimum, next_files());
    if (optimum.unbounded) {
      entry["unbounded"] = solve_json(*optimum.unbounded, next_files());
      entry["bounded_minus_unbounded"] = optimum.cost(gap.cost) - optimum.unbounded_cost(gap.cost);
    }
    optima.push_back(entry);
  }
  nlohmann::ordered_json controllers = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < gap.flights.size(); ++i) {
    const RunResult& run = gap.flights[i];
    const SegmentOptimum* optimum = gap.optimum_for(i);
    nlohmann::ordered_json entry = {
        {"label", run.spec.label},
        {"controller", run.spec.controller},
        {"status", sim::status_name(run.summary.status)},
        {"end_time_s", run.summary.end_time},
        {"cost", optimum ? number_or_null(gap.costs[i]) : nullptr},
        {"optimum", optimum ? nlohmann::ordered_json(optimum->optimum.run.spec.label) : nullptr},
        {"optimal_cost", optimum ? number_or_null(optimum->cost(gap.cost)) : nullptr},
        {"gap_percent", optimum ? number_or_null(gap.gap_percent(i)) : nullptr}};
    if (optimum && optimum->unbounded) {
      entry["unbounded_optimal_cost"] = number_or_null(optimum->unbounded_cost(gap.cost));
      entry["unbounded_gap_percent"] = number_or_null(gap.unbounded_gap_percent(i));
    }
    controllers.push_back(entry);
  }
  std::string weights = "the plant's design weights (Eq. 33-34 for the helicopter)";
  if (gap.cost == OptimalCost::deviation) {
    std::string why_not;
    if (const auto deviation = flight.deviation_cost(why_not)) weights = deviation->weights().name;
  }
  return {{"format", kOptimalityFormat},
          {"format_version", kOptimalityFormatVersion},
          {"scenario", flight.scenario().name},
          {"start_s", first.start_time()},
          {"horizon_s", first.horizon()},
          {"control_interval_s", options.control_interval},
          {"cost", {{"name", cost}, {"weights", weights}}},
          {"input_bounds", first.bounded() ? "the actuators' magnitude limits (their rate limits are not modelled)"
                                           : "none"},
          {"converged", optimality_converged(gap)},
          {"unbounded_at_most_bounded",
           first.bounded() ? nlohmann::ordered_json(unbounded_at_most_bounded(gap)) : nlohmann::ordered_json(nullptr)},
          {"optima", optima},
          {"controllers", controllers},
          {"provenance", to_json(gap.optima.front().optimum.run.provenance)}};
}

nlohmann::ordered_json write_optimality(const Flight& flight, const OptimalityGap& gap, const OptimalityOptions& options,
                                        const std::filesystem::path& out) {
  const auto comparison_file = out / "comparison.json", optimality_file = out / "optimality.json";
  for (const auto& stale : {comparison_file, optimality_file}) {
    std::error_code error;
    std::filesystem::remove(stale, error);
    if (error) throw Error("cannot remove the old " + stale.string() + ": " + error.message());
  }
  const std::vector<RunResult> runs = optimality_runs(gap);
  std::vector<RunFiles> files;
  for (const auto& run : runs) files.push_back(write_run_files(run, out));
  nlohmann::ordered_json report = optimality_json(flight, gap, options, files);
  write_file_atomically(comparison_file, comparison_json(flight, runs, files).dump(2) + "\n");
  write_file_atomically(optimality_file, report.dump(2) + "\n");
  return report;
}

}  // namespace thetad
