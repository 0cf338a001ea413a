#include "tuning/tuning_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "experiment/run_result.hpp"

namespace thetad::tuning {

namespace {

using Json = nlohmann::ordered_json;

std::vector<double> values(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

Json to_json(const Validation& v) {
  const sim::RunSummary& s = v.summary;
  const auto xyz = [](const Eigen::Vector3d& e) { return Json::array({e.x(), e.y(), e.z()}); };
  return {{"scenario", v.scenario},
          {"role", v.role},
          {"parameters", v.parameters},
          {"status", status_text(s)},
          {"rms_tracking_error_m", xyz(s.rms_tracking_error)},
          {"max_tracking_error_m", xyz(s.max_tracking_error)},
          {"cost", s.cost}};
}

const char* weighting(const FitOptions& options) {
  return options.weighting == Weighting::relative ? "relative" : "absolute";
}

}  // namespace

double TuningReport::rms_sigma_error_default() const {
  return std::sqrt(fit.start_residual / static_cast<double>(samples));
}

double TuningReport::rms_sigma_error_tuned() const { return std::sqrt(fit.residual / static_cast<double>(samples)); }

bool TuningReport::any_diverged() const {
  return std::any_of(validations.begin(), validations.end(),
                     [](const Validation& v) { return v.summary.status != sim::RunStatus::completed; });
}

Json to_json(const TuningReport& r) {
  Json j;
  j["scenario"] = r.scenario;
  j["seed"] = r.seed;
  j["record"] = {{"samples", r.samples}, {"reused", r.record_reused}};
  j["terms"] = r.terms;
  j["algorithm"] = r.options.algorithm;
  j["weighting"] = weighting(r.options);
  j["bounds"] = {{"k", {r.options.k_lower, r.options.k_upper}}, {"l", {r.options.l_lower, r.options.l_upper}}};
  j["k"] = values(r.fit.k);
  j["l"] = values(r.fit.l);
  j["residual_default"] = r.fit.start_residual;
  j["residual_tuned"] = r.fit.residual;
  j["rms_sigma_error_default"] = r.rms_sigma_error_default();
  j["rms_sigma_error_tuned"] = r.rms_sigma_error_tuned();
  j["evaluations"] = r.fit.evaluations;
  j["stop_reason"] = r.fit.stop_reason;
  j["expansion_seconds"] = r.expansion_seconds;
  j["fit_seconds"] = r.fit.seconds;
  j["threads"] = r.threads;
  j["validation"] = Json::array();
  for (const Validation& v : r.validations) j["validation"].push_back(to_json(v));
  j["provenance"] = to_json(r.provenance);
  return j;
}

std::string tuned_settings_file(const TuningReport& report, const YAML::Node& settings) {
  YAML::Node file(YAML::NodeType::Map);
  file["theta-d"] = settings;
  YAML::Emitter emitter;
  emitter.SetDoublePrecision(17);
  emitter << file;
  return "# thetad tune on " + report.scenario + " (" + report.options.algorithm + ", " + weighting(report.options) +
         " residual, seed " + std::to_string(report.seed) + ")\n" + emitter.c_str() + "\n";
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
