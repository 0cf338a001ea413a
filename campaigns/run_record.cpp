#include "campaigns/run_record.hpp"

#include <limits>

#include "experiment/result_json.hpp"

namespace thetad {

const std::vector<MetricColumn>& metric_columns() {
  static const std::vector<MetricColumn> columns = {
      {"rms_error_x_m", false},      {"rms_error_y_m", false},
      {"rms_error_z_m", false},      {"rms_error_m", false},
      {"max_error_x_m", false},      {"max_error_y_m", false},
      {"max_error_z_m", false},      {"max_axis_error_m", false},
      {"cost", false},               {"cost_dev", false},
      {"rms_command_T_mr_N", false}, {"rms_command_delta_ped_rad", false},
      {"rms_command_delta_col_rad", false}, {"rms_command_delta_lon_rad", false},
      {"rms_command_delta_lat_rad", false},
      {"in_flight_step_time_mean_us", true}, {"in_flight_step_time_median_us", true},
      {"in_flight_step_time_p99_us", true},  {"wall_time_s", true},
      {"missed_deadlines", false},            {"longest_missed_run", false},
      {"skipped_samples", false},
  };
  return columns;
}

RunRecord make_record(const PlannedRun& run, const FactorValues& factors, const RunResult& result) {
  const sim::RunSummary& s = result.summary;
  RunRecord record;
  record.index = run.index;
  record.cell = run.cell;
  record.draw = run.draw;
  record.scenario = result.provenance.scenario_name;
  record.label = result.spec.label;
  record.controller = result.spec.controller;
  record.seed = run.seed;
  record.factors = factors;
  record.status = sim::status_name(s.status);
  record.reason = s.reason;
  record.information = information_set(result);
  record.end_time_s = s.end_time;
  record.controller_samples = s.controller_samples;
  // Each figure as the result file names it (docs/glossary.md), NULL in the database where the run
  // has none: no timing under --no-timing, no flight computer, J_dev without trims, and a plant's
  // own tracked states and inputs where the columns name the helicopter's.
  const nlohmann::ordered_json summary = summary_json(s);
  const double none = std::numeric_limits<double>::quiet_NaN();
  for (const MetricColumn& column : metric_columns()) {
    const std::string name(column.name);
    if (name == "wall_time_s")
      record.metrics.push_back(s.settings.measure_compute_time ? result.wall_time_s : none);
    else if (summary.contains(name) && summary.at(name).is_number())
      record.metrics.push_back(summary.at(name).get<double>());
    else
      record.metrics.push_back(none);
  }
  return record;
}

nlohmann::json to_json(const RunRecord& r) {
  nlohmann::json factors = nlohmann::json::array();
  for (const auto& [name, value] : r.factors) factors.push_back({name, value});
  return {{"index", r.index},           {"cell", r.cell},         {"draw", r.draw},
          {"scenario", r.scenario},     {"label", r.label},       {"controller", r.controller},
          {"seed", r.seed},             {"factors", factors},     {"status", r.status},
          {"reason", r.reason},         {"information", r.information},
          {"end_time_s", r.end_time_s}, {"controller_samples", r.controller_samples},
          {"metrics", r.metrics}};
}

RunRecord record_from_json(const nlohmann::json& j) {
  RunRecord r;
  r.index = j.at("index").get<std::int64_t>();
  r.cell = j.at("cell").get<int>();
  r.draw = j.at("draw").get<int>();
  r.scenario = j.at("scenario").get<std::string>();
  r.label = j.at("label").get<std::string>();
  r.controller = j.at("controller").get<std::string>();
  r.seed = j.at("seed").get<std::uint64_t>();
  for (const auto& factor : j.at("factors")) r.factors.emplace_back(factor.at(0).get<std::string>(), factor.at(1).get<double>());
  r.status = j.at("status").get<std::string>();
  r.reason = j.at("reason").get<std::string>();
  r.information = j.at("information").get<std::string>();
  r.end_time_s = j.at("end_time_s").get<double>();
  r.controller_samples = j.at("controller_samples").get<std::int64_t>();
  // JSON has no NaN: a figure the run does not have (J_dev, timing) travels as null.
  for (const auto& value : j.at("metrics"))
    r.metrics.push_back(value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>());
  return r;
}

}  // namespace thetad
