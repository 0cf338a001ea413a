#include "tuning/tuning_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/sim/run_summary.hpp"

namespace thetad::tuning {

namespace {

using Json = nlohmann::ordered_json;

std::vector<double> values(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// NaN (an interval of one pair) as null: JSON has no NaN.
Json number(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

Json to_json(const PairedComparison& c) {
  return {{"metric", metric_name(c.metric)},
          {"default_median", c.default_median},
          {"tuned_median", c.tuned_median},
          {"difference_median", c.difference.median},
          {"difference_ci95", {number(c.difference.low), number(c.difference.high)}}};
}

Json to_json(const sim::RunSummary& run) {
  Json j = {{"status", sim::status_name(run.status)}, {"end_time_s", run.end_time}, {"cost", run.cost}};
  if (run.cost_dev) j["cost_dev"] = *run.cost_dev;
  j["rms_error_m"] = run.rms_tracking_error.norm();
  return j;
}

Json to_json(const HeldOutValidation& v, const std::string& tuning_scenario) {
  Json runs = Json::array();
  for (std::size_t i = 0; i < v.seeds.size(); ++i)
    runs.push_back({{"seed", v.seeds[i]}, {"default", to_json(v.default_runs[i])}, {"tuned", to_json(v.tuned_runs[i])}});
  Json j = {{"scenario", v.scenario},
          {"role", v.scenario == tuning_scenario ? "tuning_scenario" : "held_out_scenario"},
          {"draws", v.seeds.size()},
          {"pairs", v.pairs()},
          {"default_not_completed", v.default_not_completed()},
          {"tuned_not_completed", v.tuned_not_completed()},
          {"bootstrap", {{"method", "percentile"}, {"confidence", 0.95}, {"resamples", v.resamples}, {"seed", v.bootstrap_seed}}},
          {"cost", to_json(v.cost)},
          {"rms_error_m", to_json(v.rms_error)}};
  if (v.cost_dev) j["cost_dev"] = to_json(*v.cost_dev);
  j["runs"] = runs;
  return j;
}

Json to_json(const ObjectiveSettings& o) {
  Json j = {{"name", objective_name(o.objective)}};
  switch (o.objective) {
    case Objective::sigma:
      j["weighting"] = o.weighting == Weighting::relative ? "relative" : "absolute";
      j["every"] = o.every;
      break;
    case Objective::entries:
      j["entry_floor"] = o.entry_floor;
      j["every"] = o.every;
      break;
    case Objective::closed_loop:
      j["metric"] = metric_name(o.metric);
      j["training_seeds"] = o.training_seeds;
      break;
  }
  return j;
}

}  // namespace

const char* objective_name(Objective objective) {
  switch (objective) {
    case Objective::sigma: return "sigma";
    case Objective::entries: return "entries";
    case Objective::closed_loop: return "closed-loop";
  }
  return "";
}

Objective parse_objective(const std::string& name) {
  for (const Objective o : {Objective::sigma, Objective::entries, Objective::closed_loop})
    if (name == objective_name(o)) return o;
  throw Error("tuning: unknown objective '" + name + "' (known: sigma, entries, closed-loop)");
}

bool TuningReport::any_not_completed() const {
  return std::any_of(validations.begin(), validations.end(), [](const HeldOutValidation& v) {
    return v.default_not_completed() > 0 || v.tuned_not_completed() > 0;
  });
}

Json to_json(const TuningReport& r) {
  Json j;
  j["format"] = kTuningFormat;
  j["format_version"] = kTuningFormatVersion;
  j["scenario"] = r.scenario;
  j["seed"] = r.seed;
  j["objective"] = to_json(r.objective);
  if (r.objective.objective != Objective::closed_loop) {
    j["record_samples"] = r.samples;
    j["record_reused"] = r.record_reused;
  }
  j["controller"] = r.controller;
  j["parameters"] = {{"kind", r.parameters}, {"names", r.parameter_names}, {"lower", values(r.box.lower)},
                     {"upper", values(r.box.upper)}, {"start", values(r.box.start)}, {"tuned", values(r.fit.x)}};
  j["terms"] = r.terms;
  j["algorithm"] = r.options.algorithm;
  j["budget"] = {{"evaluations", r.options.max_local_evaluations}, {"seconds", r.options.max_seconds}};
  if (r.parameters == "series") {
    j["bounds"] = {{"k", {r.options.k_lower, r.options.k_upper}}, {"l", {r.options.l_lower, r.options.l_upper}}};
    j["k"] = values(r.fit.k);
    j["l"] = values(r.fit.l);
  }
  j["default_objective"] = r.fit.start_residual;
  j["tuned_objective"] = r.fit.residual;
  j["default_" + r.figure] = r.figure_default;
  j["tuned_" + r.figure] = r.figure_tuned;
  j["evaluations"] = r.fit.evaluations;
  j["stop_reason"] = r.fit.stop_reason;
  j["setup_time_s"] = r.setup_seconds;
  j["fit_time_s"] = r.fit.seconds;
  j["threads"] = r.threads;
  j["warnings"] = r.warnings;
  j["validation"] = Json::array();
  for (const HeldOutValidation& v : r.validations) j["validation"].push_back(to_json(v, r.scenario));
  j["provenance"] = to_json(r.provenance);
  return j;
}

std::string tuned_settings_file(const TuningReport& report, const YAML::Node& settings) {
  YAML::Node file(YAML::NodeType::Map);
  file[report.controller] = settings;
  YAML::Emitter emitter;
  emitter.SetDoublePrecision(17);
  emitter << file;
  return "# thetad tune on " + report.scenario + " (objective " + objective_name(report.objective.objective) + ", " +
         report.options.algorithm + ", seed " + std::to_string(report.seed) + ")\n" + emitter.c_str() + "\n";
}

std::string sigma_curves_csv(const SigmaMatch& match, const TuningRecord& record, const FitResult& fit) {
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(match.parameters());
  const Eigen::VectorXd sigma_default = match.sigma(ones, ones), sigma_tuned = match.sigma(fit.k, fit.l);
  std::string curves = "t_s,sigma_sdre,sigma_theta_d_default,sigma_theta_d_tuned\n";
  char line[128];
  for (Eigen::Index k = 0; k < match.samples(); ++k) {
    std::snprintf(line, sizeof line, "%.6f,%.10g,%.10g,%.10g\n", record.time[static_cast<std::size_t>(k)],
                  match.sigma_sdre()[k], sigma_default[k], sigma_tuned[k]);
    curves += line;
  }
  return curves;
}

}  // namespace thetad::tuning
