#include "experiment/replay.hpp"

#include <array>
#include <string_view>

#include "core/error.hpp"
#include "experiment/flight.hpp"
#include "experiment/result_json.hpp"
#include "experiment/sha256.hpp"
#include "experiment/json_file.hpp"

namespace thetad {

namespace {

using Json = nlohmann::ordered_json;

// The figures that decide whether two runs are the same run (not the wall-clock ones).
constexpr const char* kCompared[] = {"status",           "reason",           "end_time_s",         "controller_samples",
                                     "parameter_factors", "controller_counters", "tracking_error_m", "control_effort",
                                     "saturation",       "cost"};

RunControls controls_of(const Json& settings, const Json& provenance) {
  RunControls controls;
  controls.seed = provenance.at("seed").get<std::uint64_t>();
  const auto vector = [](const Json& entries) { return Eigen::Vector3d(entries.get<std::array<double, 3>>().data()); };
  if (provenance.contains("initial_offset_m")) controls.initial_offset = vector(provenance["initial_offset_m"]);
  if (provenance.contains("initial_attitude_offset_rad"))
    controls.initial_attitude_offset = vector(provenance["initial_attitude_offset_rad"]);
  if (provenance.contains("trajectory_speed_scale"))
    controls.speed_scale = provenance["trajectory_speed_scale"].get<double>();
  controls.duration = settings.at("duration_s").get<double>();
  controls.dt = settings.at("dt_s").get<double>();
  controls.log_every = settings.at("log_every").get<int>();
  controls.summary_only = !settings.at("keep_log").get<bool>();
  controls.timing = settings.at("measure_compute_time").get<bool>();
  controls.parameter_uncertainty = settings.at("parameter_uncertainty").get<bool>();
  controls.wind_gust = settings.at("wind_gust").at("enabled").get<bool>();
  const Json& noise = settings.at("noise");
  controls.measurement_noise = noise.at("measurement").get<bool>();
  controls.actuator_noise = noise.at("actuator").get<bool>();
  controls.wind_noise = noise.at("wind_component").get<bool>();
  controls.induced_velocity_noise = noise.at("induced_velocity").get<bool>();
  // Results written before the actuator limits existed flew without them.
  controls.actuator_limits = settings.contains("actuator_limits") && settings["actuator_limits"].at("enabled").get<bool>();
  // Files written before the disturbance scales existed flew at the paper's strengths.
  controls.uncertainty_scale = settings.value("uncertainty_scale", 1.0);
  controls.noise_scale = noise.value("scale", 1.0);
  controls.gust_scale = settings.at("wind_gust").value("amplitude_scale", 1.0);
  controls.gust_onset = settings.at("wind_gust").value("onset_s", 0.0);
  return controls;
}

}  // namespace

Replay replay(const std::filesystem::path& result_file, Progress* progress) {
  const Json recorded = read_json_file(result_file);
  if (!recorded.is_object() || recorded.value("format", "") != kRunFormat)
    throw Error(result_file.string() + ": not a thetad run result (format " + std::string(kRunFormat) + ")");
  try {
    const Json& provenance = recorded.at("provenance");
    const std::string scenario = provenance.at("scenario").at("file").get<std::string>();
    const std::string sha = provenance.at("scenario").at("sha256").get<std::string>();
    if (sha256_of_file(scenario) != sha)
      throw Error(result_file.string() + ": the scenario " + scenario +
                  " has changed since the run (its SHA-256 differs from the recorded one)");
    const Flight flight(scenario, controls_of(recorded.at("settings"), provenance));
    ControllerSpec spec{recorded.at("label").get<std::string>(), recorded.at("controller").get<std::string>(),
                        json_to_yaml(recorded.at("controller_settings")), result_file.string(), {}};
    PreparedController prepared = flight.prepare(spec);
    Replay outcome{flight.fly(prepared, progress), {}};
    const Json again = summary_json(outcome.result.summary);
    for (const char* field : kCompared) {
      if (std::string_view(field) == "saturation" && !recorded.contains(field)) continue;  // an older result
      if (again.at(field) != recorded.at(field))
        outcome.differences.push_back(std::string(field) + ": recorded " + recorded.at(field).dump() + ", replayed " +
                                      again.at(field).dump());
    }
    return outcome;
  } catch (const Json::exception& error) {
    throw Error(result_file.string() + ": incomplete run result: " + error.what());
  }
}

}  // namespace thetad
