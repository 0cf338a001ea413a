#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/sim/simulator.hpp"
#include "experiment/run_result.hpp"

namespace thetad {

// The run files' JSON: what a result *is* on disk. Field names carry units.

// The summary (status, the simulation settings, and the metrics as flat keys named as
// docs/glossary.md gives them: per tracked axis rms_error_x_m ... and max_error_x_m ..., the 3-D
// rms_error_m and max_axis_error_m (the tracked states' command unit last; none for a plant that
// tracks nothing), rms_command_<channel>_<unit>, saturated_{magnitude,rate}_<channel> and
// saturated_samples, cost, cost_dev and cost_dev_weights, and in_flight_step_time_{mean,median,p99}_us
// unless the time was not measured; "definitions" says what they mean).
nlohmann::ordered_json summary_json(const sim::RunSummary& summary);

// The log's columns as written: the run's `schema` without the wall-clock column when the run
// measured no time (so two runs with one seed give the same bytes).
std::vector<LogColumn> log_columns(const std::vector<LogColumn>& schema, bool timing);

// The whole result: {"format", "label", "controller" (registered name), the summary's fields,
// "controller_settings", "settings_source", "log" (the CSV's file name, SHA-256, rows and columns;
// null when summary-only), "provenance", "wall_time_s" (with timing only)}.
// Its "format_version" says which fields it has; readers take every earlier version:
//   1 (no "format_version"): the helicopter's flights only; the scenario by file and SHA-256.
//   2: "log.columns" lists the CSV's columns (a plant's own); "provenance.plant" names the plant,
//      "provenance.scenario.text" holds the scenario as flown, "provenance.initial_state" where a
//      plant's flight started.
//   3: "settings" holds "turbulence", "discrete_gusts", "sensor_noise" and "servos" (docs/model.md
//      §15); a file without them flew with all of them off, which replay restores. A thetad that
//      reads up to version 2 refuses these files rather than replay them without their disturbances.
//   4: the names of docs/glossary.md: the metrics are flat keys (summary_json above) where version 3
//      grouped them ("tracking_error_m": {"rms": [...], "max": [...]}, "control_effort", "saturation",
//      "cost": {"J"}, "cost_dev": {"J_dev", "weights"}, "compute_time_ns" in ns); the in-flight step
//      times are in µs; "wall_seconds" is "wall_time_s"; "settings" says "gust_scale", "gust_onset_s",
//      "timing" and "summary_only" for "wind_gust.amplitude_scale", "wind_gust.onset_s",
//      "measure_compute_time" and "keep_log" (negated); the log's wall-clock column is
//      in_flight_step_time_ns (compute_ns). The 3-D rms_error_m and max_axis_error_m are new, and
//      "settings" holds "parameter_deviations" when Table 1's were fixed instead of drawn.
//      Readers take earlier files through with_current_names (experiment/result_names.hpp).
inline constexpr const char* kRunFormat = "thetad-run-1";
inline constexpr int kRunFormatVersion = 4;
// The version of `result` (1 when it says none); throws thetad::Error naming `file` when it is of
// a newer thetad than this one.
int run_format_version(const nlohmann::ordered_json& result, const std::string& file);
struct LogFile {
  std::string file;    // name in the result's folder
  std::string sha256;
  long long rows = 0;
};
nlohmann::ordered_json result_json(const RunResult& result, const LogFile* log);

// A YAML tree as JSON: scalars that read as numbers or booleans become numbers or booleans.
nlohmann::ordered_json yaml_to_json(const YAML::Node& node);
// And back, for rebuilding a controller from a result file.
YAML::Node json_to_yaml(const nlohmann::ordered_json& json);

}  // namespace thetad
