#include "settings/run_settings.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace thetad {

namespace {

using Json = nlohmann::ordered_json;

// "settings.noise.scale" as a JSON pointer.
Json::json_pointer pointer(std::string_view dotted) {
  std::string text(1, '/');
  for (const char c : dotted) text.push_back(c == '.' ? '/' : c);
  return Json::json_pointer(text);
}

// The keys of a row's file_key ("duration, simulation.duration"), each dotted.
std::vector<std::string_view> file_keys(std::string_view listed) {
  std::vector<std::string_view> keys;
  for (std::size_t start = 0; start < listed.size();) {
    const std::size_t end = std::min(listed.find(", ", start), listed.size());
    keys.push_back(listed.substr(start, end - start));
    start = end + 2;
  }
  return keys;
}

// The fields that the rows' file keys put directly in the block `path` ("simulation": "seed", "dt",
// ..., "disturbances", "wind"), each once, in table order, then `extra`.
std::vector<std::string_view> fields_of_block(std::string_view path, std::initializer_list<std::string_view> extra) {
  std::vector<std::string_view> fields;
  const auto add = [&](std::string_view field) {
    if (std::find(fields.begin(), fields.end(), field) == fields.end()) fields.push_back(field);
  };
  for (const RunSetting& setting : run_settings()) {
    for (const std::string_view key : file_keys(setting.file_key)) {
      if (key.size() <= path.size() || !key.starts_with(path) || key[path.size()] != '.') continue;
      const std::string_view rest = key.substr(path.size() + 1);
      add(rest.substr(0, rest.find('.')));
    }
  }
  for (const std::string_view field : extra) add(field);
  return fields;
}

}  // namespace

RunControls read_simulation_block(const Settings& simulation, const std::filesystem::path& folder,
                                  std::initializer_list<std::string_view> scenario_fields) {
  const Settings disturbances(simulation.has("disturbances") ? simulation.node()["disturbances"] : YAML::Node(),
                              "simulation.disturbances");
  simulation.allow_only(fields_of_block("simulation", scenario_fields));
  disturbances.allow_only(fields_of_block("simulation.disturbances", {}));
  RunControls controls;
  for (const RunSetting& setting : run_settings()) {
    if (!setting.read) continue;
    // The block of the last key; the row's reader knows its other keys, if any.
    const std::string_view key = file_keys(setting.file_key).back();
    const std::size_t dot = key.rfind('.');
    const std::string_view block = key.substr(0, dot);
    if (block != "simulation" && block != "simulation.disturbances")
      throw Error("run setting " + std::string(setting.name) + ": a reader for a field outside simulation and "
                  "simulation.disturbances (" + std::string(key) + ")");
    setting.read({block == "simulation" ? simulation : disturbances, std::string(key.substr(dot + 1)), folder},
                 controls);
  }
  return controls;
}

bool RunSetting::names(std::string_view factor) const {
  if (!is_family()) return factor == name || (!earlier_name.empty() && factor == earlier_name);
  const std::string_view prefix = name.substr(0, name.find('.') + 1);
  return factor.size() > prefix.size() && factor.substr(0, prefix.size()) == prefix;
}

void RunSetting::set(std::string_view factor, double value, RunControls& controls) const {
  if (is_family())
    apply_named(factor, value, controls);
  else
    apply(value, controls);
}

const RunSetting* find_run_setting(std::string_view name) {
  for (const RunSetting& setting : run_settings()) {
    if (setting.name == name || (!setting.earlier_name.empty() && setting.earlier_name == name)) return &setting;
  }
  return nullptr;
}

Json settings_json(const sim::SimulationSettings& settings) {
  Json json;
  for (const RunSetting& setting : run_settings()) {
    if (setting.record) setting.record(settings, json);
  }
  return json;
}

RunControls recorded_controls(const Json& result, int version) {
  RunControls controls;
  for (const RunSetting& setting : run_settings()) {
    if (setting.result_key.empty()) continue;
    const Json::json_pointer key = pointer(setting.result_key);
    if (!result.contains(key) && version <= setting.absent_until) {
      if (setting.before) setting.before(controls);
      continue;
    }
    setting.replay(result.at(key), controls);  // at() throws for a field the version must have
  }
  return controls;
}

}  // namespace thetad
