// The plant's rows of the run settings' table (settings/plant_setting_rows.hpp). Flight applies
// them (Flight::plant_flight; the helicopter's scenarios refuse them).
#include "settings/plant_setting_rows.hpp"

#include <charconv>
#include <cmath>
#include <map>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace thetad {

namespace {

using Json = nlohmann::ordered_json;

// What the plant checks beyond this (its own ranges) it says when it is built.
double plant_factor_value(double value) {
  if (!std::isfinite(value)) throw Error("must be a finite number");
  return value;
}

// I of initial_state.I: a state's index, a whole decimal from 0.
int initial_state_index(std::string_view text) {
  int index = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), index);
  if (error != std::errc() || end != text.data() + text.size() || index < 0)
    throw Error("expected initial_state.I with I a state's index (0, 1, ...), got initial_state." + std::string(text));
  return index;
}

}  // namespace

std::vector<RunSetting> plant_setting_rows() {
  return {
      {.name = "plant.NAME",
       .description = "the plant's own setting NAME (plant.epsilon for the tora), over its scenario's plant_settings",
       .apply_named = [](std::string_view name, double v, RunControls& c) {
         c.plant_settings[std::string(name.substr(name.find('.') + 1))] = plant_factor_value(v);
       },
       .result_key = "provenance.plant_settings",
       .replay = [](const Json& v, RunControls& c) { c.plant_settings = v.get<std::map<std::string, double>>(); },
       .absent_until = RunSetting::kEveryVersion},
      {.name = "initial_state.I",
       .description = "entry I (from 0) of the plant's initial state, in place of its scenario's",
       .apply_named = [](std::string_view name, double v, RunControls& c) {
         c.initial_state_entries[initial_state_index(name.substr(name.find('.') + 1))] = plant_factor_value(v);
       },
       // The initial state flown, every entry: a replay starts where the run started.
       .result_key = "provenance.initial_state",
       .replay = [](const Json& v, RunControls& c) {
         const std::vector<double> x0 = v.get<std::vector<double>>();
         for (std::size_t i = 0; i < x0.size(); ++i) c.initial_state_entries[static_cast<int>(i)] = x0[i];
       },
       .absent_until = RunSetting::kEveryVersion},
  };
}

}  // namespace thetad
