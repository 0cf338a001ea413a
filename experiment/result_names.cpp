#include "experiment/result_names.hpp"

#include <string>
#include <string_view>

#include "core/sim/simulator.hpp"
#include "experiment/result_json.hpp"

namespace thetad {

namespace {

using Json = nlohmann::ordered_json;

// "tracking_error_m": {"axes", "rms", "max"} (versions 1-3; "tracking_error" for a unitless
// command) as rms_error_<axis>_<unit> and max_error_<axis>_<unit>.
constexpr std::string_view kTrackingError = "tracking_error";

void add_tracking_errors(const std::string& key, const Json& group, Json& out) {
  const std::string unit = key.size() > kTrackingError.size() + 1 ? key.substr(kTrackingError.size() + 1) : "";
  const auto name = [&unit](const std::string& quantity) { return unit.empty() ? quantity : quantity + "_" + unit; };
  const Json& axes = group.at("axes");
  for (std::size_t i = 0; i < axes.size(); ++i)
    out[name("rms_error_" + axes[i].get<std::string>())] = group.at("rms").at(i);
  for (std::size_t i = 0; i < axes.size(); ++i)
    out[name("max_error_" + axes[i].get<std::string>())] = group.at("max").at(i);
}

// "saturation": {"channels", "magnitude", "rate", "samples_limited"}.
void add_saturation(const Json& group, Json& out) {
  const Json& channels = group.at("channels");
  for (std::size_t i = 0; i < channels.size(); ++i)
    out["saturated_magnitude_" + channels[i].get<std::string>()] = group.at("magnitude").at(i);
  for (std::size_t i = 0; i < channels.size(); ++i)
    out["saturated_rate_" + channels[i].get<std::string>()] = group.at("rate").at(i);
  out["saturated_samples"] = group.at("samples_limited");
}

Json current_settings(const Json& settings) {
  Json out;
  for (const auto& [key, value] : settings.items()) {
    if (key == "keep_log") {
      out["summary_only"] = !value.get<bool>();
    } else if (key == "measure_compute_time") {
      out["timing"] = value;
    } else if (key == "wind_gust") {
      Json gust = value;
      gust.erase("amplitude_scale");
      gust.erase("onset_s");
      out[key] = gust;
      if (value.contains("amplitude_scale")) out["gust_scale"] = value["amplitude_scale"];
      if (value.contains("onset_s")) out["gust_onset_s"] = value["onset_s"];
    } else {
      out[key] = value;
    }
  }
  return out;
}

}  // namespace

LogColumn current_log_column(LogColumn column) {
  const LogColumn earlier = earlier_step_time_column();
  if (column.name == earlier.name && column.unit == earlier.unit) return sim::step_time_column();
  return column;
}

Json with_current_names(Json result) {
  if (result.value("format_version", 1) >= kRunFormatVersion) return result;
  Json out;
  for (const auto& [key, value] : result.items()) {
    if (key.starts_with(kTrackingError) && value.is_object()) {
      add_tracking_errors(key, value, out);
    } else if (key == "control_effort") {
      for (const auto& [channel, rms] : value.at("rms").items()) out["rms_command_" + channel] = rms;
    } else if (key == "saturation") {
      add_saturation(value, out);
    } else if (key == "cost" && value.is_object()) {
      out["cost"] = value.at("J");
    } else if (key == "cost_dev" && value.is_object()) {
      out["cost_dev"] = value.at("J_dev");
      out["cost_dev_weights"] = value.value("weights", Json(nullptr));
    } else if (key == "compute_time_ns") {
      for (const char* statistic : {"mean", "median", "p99"})
        out[std::string("in_flight_step_time_") + statistic + "_us"] = value.at(statistic).get<double>() * 1e-3;
    } else if (key == "wall_seconds") {
      out["wall_time_s"] = value;
    } else if (key == "settings") {
      out[key] = current_settings(value);
    } else if (key == "log" && value.is_object() && value.contains("columns")) {
      out[key] = value;
      for (Json& column : out[key]["columns"]) {
        column["name"] =
            current_log_column({column.at("name").get<std::string>(), column.at("unit").get<std::string>()}).name;
      }
    } else {
      out[key] = value;
    }
  }
  return out;
}

}  // namespace thetad
