#include "experiment/run_settings.hpp"

namespace thetad {

namespace {

using Json = nlohmann::ordered_json;

// "settings.noise.scale" as a JSON pointer.
Json::json_pointer pointer(std::string_view dotted) {
  std::string text(1, '/');
  for (const char c : dotted) text.push_back(c == '.' ? '/' : c);
  return Json::json_pointer(text);
}

}  // namespace

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
