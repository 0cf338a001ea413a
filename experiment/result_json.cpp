#include "experiment/result_json.hpp"

#include <cmath>
#include <string_view>

#include "core/error.hpp"
#include "settings/run_settings.hpp"

namespace thetad {

namespace {

using Json = nlohmann::ordered_json;

// A certificate's worst value: a number, "inf" (the stabilizability margin of a pair with nothing
// to stabilize) or null (no sample had a value), which JSON numbers cannot tell apart.
Json certificate_value(double value) {
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  return std::isnan(value) ? Json(nullptr) : Json(value);
}

// The worst value of each of the controller's certificates and when (docs/model.md §8.4).
Json certificates_json(const std::vector<CertificateWorst>& certificates) {
  Json j = Json::object();
  for (const CertificateWorst& worst : certificates) {
    const bool largest = worst.certificate.worst == ControllerColumn::Worst::largest;
    j[worst.certificate.column.header()] = {{"worst", largest ? "largest" : "smallest"},
                                            {"value", certificate_value(worst.value)},
                                            {"t_s", std::isnan(worst.t) ? Json(nullptr) : Json(worst.t)}};
  }
  return j;
}

// What the summary's metrics mean, for a reader of the file without the docs (docs/glossary.md has
// them all).
Json definitions(const sim::RunSummary& summary) {
  Json j = Json::object();
  if (!summary.tracked.empty())
    j["rms_error"] = "RMS over the controller samples of the true tracked state minus its command, per axis and in "
                     "3-D; max_error the largest magnitude per axis, max_axis_error the largest of those";
  j["rms_command"] = "RMS of the commanded input per channel over the controller samples";
  j["saturated"] = "controller samples whose applied input the actuator limits changed, per channel and in all";
  j["cost"] = "J = 1/2 sum_k (V_track' Q V_track + u_cmd' R u_cmd) T_c, Eq. 32 with Q, R of Eqs. 33-34, true V_track";
  j["cost_dev"] = "J_dev = 1/2 sum_k (e' Q e + (u_cmd - u_r)' R (u_cmd - u_r)) T_c, e the true state's deviation "
                  "from the commanded motion and its trim, u_r the trim's input (docs/model.md §7.2); one Q, R for "
                  "every controller, named in cost_dev_weights";
  if (summary.computer)
    j["missed_deadlines"] = "computations of the flight computer whose latency exceeded the controller period "
                           "(docs/model.md §15.7); longest_missed_run the most in a row; skipped_samples the samples "
                           "that started no computation because it was busy; aborted_computations those stopped "
                           "at their deadline";
  if (summary.settings.measure_compute_time)
    j["in_flight_step_time"] = "wall time of each control() call inside the flight, with the simulation around it: "
                               "noisy; thetad bench measures the per-step cost";
  return j;
}

// A channel's count; a summary made without the limiter's counts (none per channel) has none.
std::int64_t count_of(const std::vector<std::int64_t>& counts, std::size_t channel) {
  return channel < counts.size() ? counts[channel] : 0;
}

}  // namespace

int run_format_version(const Json& result, const std::string& file) {
  const int version = result.value("format_version", 1);
  if (version > kRunFormatVersion)
    throw Error(file + ": written by a newer thetad (format_version " + std::to_string(version) + "; this one reads up to " +
                std::to_string(kRunFormatVersion) + ")");
  return version;
}

std::vector<LogColumn> log_columns(const std::vector<LogColumn>& schema, bool timing) {
  std::vector<LogColumn> columns = schema;
  if (!timing && !columns.empty() && columns.back().header() == sim::step_time_column().header()) columns.pop_back();
  return columns;
}

std::string information_set(const RunResult& result) {
  const YAML::Node feedforward = result.settings.IsMap() ? result.settings["feedforward"] : YAML::Node();
  return feedforward && feedforward.IsScalar() ? feedforward.as<std::string>() : "own";
}

std::string status_text(const sim::RunSummary& summary) {
  if (summary.status == sim::RunStatus::completed) return "completed";
  char text[64];
  std::snprintf(text, sizeof text, "%s at %.3f s", sim::status_name(summary.status), summary.end_time);
  return text;
}

Json summary_json(const sim::RunSummary& summary) {
  Json j;
  j["controller_name"] = summary.controller;
  j["seed"] = summary.settings.seed;
  j["status"] = sim::status_name(summary.status);
  j["reason"] = summary.reason;
  j["end_time_s"] = summary.end_time;
  j["controller_samples"] = summary.controller_samples;
  j["model_options"] = summary.model_options;
  Json factors = Json::object();
  for (const auto& [name, factor] : summary.parameter_factors) factors[name] = factor;
  j["parameter_factors"] = factors;
  Json counters = Json::object();
  for (const auto& [name, count] : summary.controller_counters) counters[name] = count;
  j["controller_counters"] = counters;
  if (!summary.certificates.empty()) j["certificates"] = certificates_json(summary.certificates);
  j["settings"] = settings_json(summary.settings);
  // Metrics are flat keys, the quantity first and the unit last (docs/glossary.md "Naming rules").
  if (!summary.tracked.empty()) {
    const std::string unit = summary.tracked.front().command.unit;
    const auto key = [&unit](const std::string& quantity) { return unit.empty() ? quantity : quantity + "_" + unit; };
    for (std::size_t i = 0; i < summary.tracked.size(); ++i)
      j[key("rms_error_" + summary.tracked[i].axis)] = summary.rms_tracking_error[static_cast<Eigen::Index>(i)];
    j[key("rms_error")] = summary.rms_tracking_error.norm();
    for (std::size_t i = 0; i < summary.tracked.size(); ++i)
      j[key("max_error_" + summary.tracked[i].axis)] = summary.max_tracking_error[static_cast<Eigen::Index>(i)];
    j[key("max_axis_error")] = summary.max_tracking_error.maxCoeff();
  }
  for (std::size_t k = 0; k < summary.inputs.size(); ++k)
    j["rms_command_" + summary.inputs[k].header()] = summary.command_rms[static_cast<Eigen::Index>(k)];
  for (std::size_t k = 0; k < summary.inputs.size(); ++k)
    j["saturated_magnitude_" + summary.inputs[k].name] = count_of(summary.saturation.magnitude, k);
  for (std::size_t k = 0; k < summary.inputs.size(); ++k)
    j["saturated_rate_" + summary.inputs[k].name] = count_of(summary.saturation.rate, k);
  j["saturated_samples"] = summary.saturation.samples_limited;
  if (summary.computer) {
    const sim::ComputerCounts& c = *summary.computer;
    j["computations"] = c.computations;
    j["missed_deadlines"] = c.missed_deadlines;
    j["longest_missed_run"] = c.longest_missed_run;
    j["skipped_samples"] = c.skipped_samples;
    j["aborted_computations"] = c.aborted;
    j["max_latency_s"] = c.max_latency;
    j["mean_latency_s"] = c.mean_latency;
  }
  j["cost"] = summary.cost;
  j["cost_dev"] = summary.cost_dev ? Json(*summary.cost_dev) : Json(nullptr);
  j["cost_dev_weights"] = summary.cost_dev_weights.empty() ? Json(nullptr) : Json(summary.cost_dev_weights);
  if (summary.settings.measure_compute_time) {
    j["in_flight_step_time_mean_us"] = summary.compute_ns_mean * 1e-3;
    j["in_flight_step_time_median_us"] = summary.compute_ns_median * 1e-3;
    j["in_flight_step_time_p99_us"] = summary.compute_ns_p99 * 1e-3;
  }
  j["definitions"] = definitions(summary);
  return j;
}

Json result_json(const RunResult& result, const LogFile* log) {
  Json j;
  j["format"] = kRunFormat;
  j["format_version"] = kRunFormatVersion;
  j["label"] = result.spec.label;
  j["controller"] = result.spec.controller;
  j["controller_origin"] = result.controller_origin;
  j["information"] = information_set(result);
  j.update(summary_json(result.summary));
  j["controller_settings"] = yaml_to_json(result.settings);
  j["settings_source"] = result.spec.settings_source;
  if (log) {
    Json columns = Json::array();
    for (const auto& column : log_columns(result.log.columns, result.summary.settings.measure_compute_time))
      columns.push_back({{"name", column.name}, {"unit", column.unit}});
    j["log"] = {{"csv", log->file}, {"sha256", log->sha256}, {"rows", log->rows}, {"columns", columns}};
  } else {
    j["log"] = nullptr;
  }
  j["provenance"] = to_json(result.provenance);
  if (result.summary.settings.measure_compute_time) j["wall_time_s"] = result.wall_time_s;
  return j;
}

Json yaml_to_json(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      Json j = Json::object();
      for (const auto& item : node) j[item.first.Scalar()] = yaml_to_json(item.second);
      return j;
    }
    case YAML::NodeType::Sequence: {
      Json j = Json::array();
      for (const auto& item : node) j.push_back(yaml_to_json(item));
      return j;
    }
    case YAML::NodeType::Scalar: {
      const std::string& text = node.Scalar();
      if (text == "true" || text == "false") return text == "true";
      long long integer = 0;
      double number = 0.0;
      if (YAML::convert<long long>::decode(node, integer) && std::to_string(integer) == text) return integer;
      if (YAML::convert<double>::decode(node, number)) return number;
      return text;
    }
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      break;
  }
  return nullptr;
}

YAML::Node json_to_yaml(const Json& json) {
  if (json.is_object()) {
    YAML::Node node(YAML::NodeType::Map);
    for (const auto& [key, value] : json.items()) node[key] = json_to_yaml(value);
    return node;
  }
  if (json.is_array()) {
    YAML::Node node(YAML::NodeType::Sequence);
    for (const auto& value : json) node.push_back(json_to_yaml(value));
    return node;
  }
  if (json.is_boolean()) return YAML::Node(json.get<bool>());
  if (json.is_number_integer()) return YAML::Node(json.get<long long>());
  if (json.is_number()) return YAML::Node(json.get<double>());
  if (json.is_string()) return YAML::Node(json.get<std::string>());
  return YAML::Node(YAML::NodeType::Null);
}

}  // namespace thetad
