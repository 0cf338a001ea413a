#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/build_info.hpp"

namespace thetad {

// Everything besides the controller that decides what a run computed, and who computed it when:
// a result file carries it so that it can be told apart from another and flown again
// (`thetad run --replay`).
struct Provenance {
  BuildInfo build;
  std::string plant;            // its name in the plant registry ("helicopter")
  std::string scenario_name;
  std::string scenario_file;    // as given (absolute when it was found by name)
  std::string scenario_sha256;  // of the file's bytes
  std::string scenario_text;    // those bytes (empty for a plant's flight, which has no scenario file)
  std::string model_preset;     // "resolved" or "paper"
  std::string model_options;    // every switch, heli::ModelOptions::to_string()
  std::uint64_t seed = 0;
  double dt = 0.0;
  // The run controls that change the flight outside its simulation settings (RunControls), when
  // given: a replay needs them to fly the same run.
  std::optional<std::array<double, 3>> initial_offset;           // m, north-east-down
  std::optional<std::array<double, 3>> initial_attitude_offset;  // rad: roll, pitch, yaw
  std::optional<double> speed_scale;
  std::optional<double> course;  // rad
  // Where a plant's flight starts (a scenario's file says it for the helicopter; empty there).
  std::vector<double> initial_state;
  // A plant's settings that the run controls set over its scenario's (the factors plant.NAME).
  std::map<std::string, double> plant_settings;
  // Wall-clock facts: empty when the run was asked for byte-identical output (no timing).
  std::string host;
  std::string start_time;  // UTC, ISO 8601
};

// The build's fields, under the names a result's provenance gives them.
nlohmann::ordered_json to_json(const BuildInfo& build);
nlohmann::ordered_json to_json(const Provenance& provenance);
// The host name and the current UTC time, filled into `provenance`.
void stamp_host_and_time(Provenance& provenance);

}  // namespace thetad
