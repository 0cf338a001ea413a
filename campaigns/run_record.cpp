#include "campaigns/run_record.hpp"

#include <limits>

namespace thetad {

const std::vector<MetricColumn>& metric_columns() {
  static const std::vector<MetricColumn> columns = {
      {"rms_x_m", false},         {"rms_y_m", false},           {"rms_z_m", false},
      {"rms_error_m", false},     {"max_x_m", false},           {"max_y_m", false},
      {"max_z_m", false},         {"max_error_m", false},       {"cost", false},
      {"cost_dev", false},
      {"effort_thrust_N", false}, {"effort_pedal_rad", false},  {"effort_collective_rad", false},
      {"effort_longitudinal_rad", false}, {"effort_lateral_rad", false},
      {"compute_us_mean", true},  {"compute_us_median", true},  {"compute_us_p99", true},
      {"wall_s", true},
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
  record.controller = result.spec.label;
  record.seed = run.seed;
  record.factors = factors;
  record.status = sim::status_name(s.status);
  record.reason = s.reason;
  record.information = information_set(result);
  record.end_time = s.end_time;
  record.controller_samples = s.controller_samples;
  // rms_error: the RMS of the 3-D error's norm, sqrt(rms_x^2 + rms_y^2 + rms_z^2); max_error: the
  // largest per-axis maximum (the summary keeps the maxima per axis).
  record.metrics = {s.rms_tracking_error.x(), s.rms_tracking_error.y(), s.rms_tracking_error.z(),
                    s.rms_tracking_error.norm(), s.max_tracking_error.x(), s.max_tracking_error.y(),
                    s.max_tracking_error.z(), s.max_tracking_error.maxCoeff(), s.cost,
                    s.cost_dev.value_or(std::numeric_limits<double>::quiet_NaN())};
  for (int i = 0; i < s.command_rms.size(); ++i) record.metrics.push_back(s.command_rms[i]);
  // Without timing there is no figure to give: NULL in the database, not a 0 a reader could average.
  const bool timed = s.settings.measure_compute_time;
  const double none = std::numeric_limits<double>::quiet_NaN();
  record.metrics.insert(record.metrics.end(), {timed ? s.compute_ns_mean / 1e3 : none, timed ? s.compute_ns_median / 1e3 : none,
                                               timed ? s.compute_ns_p99 / 1e3 : none, timed ? result.wall_time_s : none});
  return record;
}

nlohmann::json to_json(const RunRecord& r) {
  nlohmann::json factors = nlohmann::json::array();
  for (const auto& [name, value] : r.factors) factors.push_back({name, value});
  return {{"index", r.index},          {"cell", r.cell},     {"draw", r.draw},
          {"scenario", r.scenario},    {"controller", r.controller}, {"seed", r.seed},
          {"factors", factors},        {"status", r.status},   {"reason", r.reason},
          {"information", r.information},
          {"end_time", r.end_time},    {"samples", r.controller_samples}, {"metrics", r.metrics}};
}

RunRecord record_from_json(const nlohmann::json& j) {
  RunRecord r;
  r.index = j.at("index").get<std::int64_t>();
  r.cell = j.at("cell").get<int>();
  r.draw = j.at("draw").get<int>();
  r.scenario = j.at("scenario").get<std::string>();
  r.controller = j.at("controller").get<std::string>();
  r.seed = j.at("seed").get<std::uint64_t>();
  for (const auto& factor : j.at("factors")) r.factors.emplace_back(factor.at(0).get<std::string>(), factor.at(1).get<double>());
  r.status = j.at("status").get<std::string>();
  r.reason = j.at("reason").get<std::string>();
  r.information = j.at("information").get<std::string>();
  r.end_time = j.at("end_time").get<double>();
  r.controller_samples = j.at("samples").get<std::int64_t>();
  // JSON has no NaN: a figure the run does not have (J_dev, timing) travels as null.
  for (const auto& value : j.at("metrics"))
    r.metrics.push_back(value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>());
  return r;
}

}  // namespace thetad
