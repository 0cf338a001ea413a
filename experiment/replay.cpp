#include "experiment/replay.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <iterator>
#include <string>
#include <vector>

#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "experiment/flight.hpp"
#include "experiment/result_json.hpp"
#include "experiment/result_names.hpp"
#include "experiment/sha256.hpp"
#include "experiment/json_file.hpp"
#include "experiment/plant_registry.hpp"
#include "settings/run_settings.hpp"

namespace thetad {

namespace {

using Json = nlohmann::ordered_json;

// The summary's fields that do not decide whether two runs are the same run: what was asked for,
// the words, and the wall-clock figures (in_flight_step_time_*).
constexpr const char* kNotCompared[] = {"controller_name", "seed", "model_options", "settings", "definitions"};

bool compared(const std::string& key) {
  return std::find(std::begin(kNotCompared), std::end(kNotCompared), key) == std::end(kNotCompared) &&
         !key.starts_with("in_flight_step_time_");
}

// The largest relative difference between a recorded and a replayed figure (numbers, or arrays
// and objects of them, entry by entry); infinity when they differ in anything but a number's
// rounding (a string, a count of entries, a number against null).
double relative_difference(const Json& recorded, const Json& replayed) {
  if (recorded.is_number() && replayed.is_number()) {
    const double a = recorded.get<double>(), b = replayed.get<double>();
    if (a == b) return 0.0;
    const double scale = std::max(std::abs(a), std::abs(b));
    return std::isfinite(scale) ? std::abs(a - b) / scale : std::numeric_limits<double>::infinity();
  }
  if (recorded.type() != replayed.type() || recorded.size() != replayed.size() ||
      (recorded.is_primitive() && recorded != replayed))
    return std::numeric_limits<double>::infinity();
  double largest = 0.0;
  if (recorded.is_array()) {
    for (std::size_t i = 0; i < recorded.size(); ++i)
      largest = std::max(largest, relative_difference(recorded[i], replayed[i]));
  } else if (recorded.is_object()) {
    for (const auto& [key, value] : recorded.items())
      largest = std::max(largest, replayed.contains(key) ? relative_difference(value, replayed.at(key))
                                                         : std::numeric_limits<double>::infinity());
  }
  return largest;
}

// The flight a result recorded: from the scenario text it recorded (version 2; a plant's scenario
// file too), or else a plant's flight without a scenario file (`--plant`) from the registry, or else
// the helicopter's scenario from its file, which must still be the recorded bytes (version 1).
Flight recorded_flight(const Json& recorded, int version, const std::string& file) {
  const Json& provenance = recorded.at("provenance");
  const RunControls controls = recorded_controls(recorded, version);
  const std::string plant = provenance.value("plant", "helicopter");
  if (plant != "helicopter" && !PlantRegistry::instance().contains(plant))
    throw Error(file + ": the run flew the plant '" + plant + "', which no loaded plug-in registers (load the " +
                "plug-in that has it with --plugin or THETAD_PLUGIN_PATH)");
  if (plant != "helicopter" && !provenance.at("scenario").contains("text")) {
    const std::vector<double> x0 = provenance.at("initial_state").get<std::vector<double>>();
    return Flight::of_plant(plant, Eigen::Map<const Eigen::VectorXd>(x0.data(), static_cast<Eigen::Index>(x0.size())),
                            controls);
  }
  const Json& scenario = provenance.at("scenario");
  const std::string scenario_file = scenario.at("file").get<std::string>();
  const std::string sha = scenario.at("sha256").get<std::string>();
  if (scenario.contains("text")) {
    const std::string text = scenario.at("text").get<std::string>();
    if (sha256_hex(text) != sha)
      throw Error(file + ": the recorded scenario text does not have the recorded SHA-256 (the file was edited)");
    return Flight::from_text(text, scenario_file, controls);
  }
  if (sha256_of_file(scenario_file) != sha)
    throw Error(file + ": the scenario " + scenario_file +
                " has changed since the run (its SHA-256 differs from the recorded one)");
  return Flight(scenario_file, controls);
}

}  // namespace

Replay replay(const std::filesystem::path& result_file, Progress* progress) {
  const Json file = read_json_file(result_file);
  if (!file.is_object() || file.value("format", "") != kRunFormat)
    throw Error(result_file.string() + ": not a thetad run result (format " + std::string(kRunFormat) + ")");
  try {
    const int version = run_format_version(file, result_file.string());
    const Json recorded = with_current_names(file);
    const Flight flight = recorded_flight(recorded, version, result_file.string());
    ControllerSpec spec{recorded.at("label").get<std::string>(), recorded.at("controller").get<std::string>(),
                        json_to_yaml(recorded.at("controller_settings")), result_file.string(), {}};
    if (!ControllerRegistry::instance().contains(spec.controller))
      throw Error(result_file.string() + ": the run flew the controller '" + spec.controller + "' (" +
                  recorded.value("controller_origin", std::string("origin not recorded")) +
                  "), which is not registered: load the plug-in that has it (--plugin PATH or THETAD_PLUGIN_PATH)");
    PreparedController prepared = flight.prepare(spec);
    Replay outcome{flight.fly(prepared, progress), {}};
    const Json again = summary_json(outcome.result.summary);
    for (const auto& [field, value] : again.items()) {
      if (!compared(field)) continue;
      if (!recorded.contains(field)) {
        // A figure that an earlier version did not record (docs/glossary.md; result_json.hpp).
        if (version < kRunFormatVersion) continue;
        outcome.differences.push_back(field + ": not recorded, replayed " + value.dump());
      } else {
        const double difference = relative_difference(recorded.at(field), value);
        if (difference > kReplayTolerance)
          outcome.differences.push_back(field + ": recorded " + recorded.at(field).dump() + ", replayed " + value.dump());
        else
          outcome.largest_difference = std::max(outcome.largest_difference, difference);
      }
    }
    if (recorded.contains("certificates") && !again.contains("certificates"))
      outcome.differences.push_back("certificates: recorded " + recorded.at("certificates").dump() + ", replayed none");
    return outcome;
  } catch (const Json::exception& error) {
    throw Error(result_file.string() + ": incomplete run result: " + error.what());
  }
}

}  // namespace thetad
