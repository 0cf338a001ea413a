#pragma once

// The kinds of rows of the run settings' table (settings/run_setting_rows.cpp) and how a row
// reads its field from a scenario file (RunSetting::read): templates over the RunControls member
// that a row sets, and the fields with rules of their own.

#include <cmath>
#include <optional>
#include <string>

#include "core/error.hpp"
#include "core/fixed_string.hpp"
#include "settings/run_controls.hpp"
#include "settings/run_settings.hpp"

namespace thetad {

// A switch: 0 off, 1 on (a campaign value is a number, and anything between would be a typo). The
// messages of these checks leave the setting's name to the caller, which knows how it was given.
bool switch_value(double value);
// A whole number (a count or a choice's position), as the int it stands for.
int whole(double value);

// A scenario file's value under the row's key, into the RunControls member `control`, when the file
// has it: a switch, a count from `min` on, or a number > 0.
template <std::optional<bool> RunControls::*control>
void read_switch(const FileField& field, RunControls& controls) {
  if (field.block.has(field.key)) controls.*control = field.block.boolean(field.key, false);
}
template <std::optional<int> RunControls::*control, int min>
void read_count(const FileField& field, RunControls& controls) {
  if (field.block.has(field.key)) controls.*control = field.block.integer(field.key, min, min);
}
template <std::optional<double> RunControls::*control>
void read_positive(const FileField& field, RunControls& controls) {
  if (!field.block.has(field.key)) return;
  const double value = field.block.number(field.key, 0.0);
  if (!(value > 0.0)) throw field.block.error(field.key, "must be > 0");
  controls.*control = value;
}

// A file's dt without controller_period_steps: the controller keeps sampling at 1 kHz with
// zero-order hold, so the plant step must divide 1 ms, and the steps follow from it.
void read_dt(const FileField& field, RunControls& controls);
// simulation.duration: > 0 and at most one simulated day (the rows' fly would refuse a longer one
// without naming the field).
void read_duration(const FileField& field, RunControls& controls);
// simulation.disturbances.parameter_deviations: {NAME: xi, ...} over Table 1's parameter names
// (absent names 0).
void read_parameter_deviations(const FileField& field, RunControls& controls);
// simulation.disturbances.measurement_noise_on: feedback_signal or absolute_state.
void read_measurement_noise_on(const FileField& field, RunControls& controls);

// A disturbance's switch: the RunControls member `control` sets the field of the flight's
// settings that `path` leads to (a member, or a block's member); `row` says the rest.
template <std::optional<bool> RunControls::*control, auto... path>
RunSetting switch_row(RunSetting row) {
  row.value = RunSetting::Value::on_off;
  row.apply = [](double v, RunControls& c) { c.*control = switch_value(v); };
  row.fly = [](const RunControls& c, sim::SimulationSettings& s) {
    if (c.*control) (s .* ... .* path) = *(c.*control);
  };
  row.replay = [](const nlohmann::ordered_json& v, RunControls& c) { c.*control = v.get<bool>(); };
  if (!row.file_key.empty()) row.read = read_switch<control>;
  return row;
}

// A multiplier of a disturbance's strength, finite and >= 0: the RunControls member `control` sets
// the field of the flight's settings that `path` leads to; `row` says the rest.
template <FixedString name, std::optional<double> RunControls::*control, auto... path>
RunSetting scale_row(RunSetting row) {
  row.name = name.value;
  row.value = RunSetting::Value::number;
  row.min = 0.0;
  row.apply = [](double v, RunControls& c) { c.*control = v; };
  row.fly = [](const RunControls& c, sim::SimulationSettings& s) {
    if (!(c.*control)) return;
    const double value = *(c.*control);
    if (!(value >= 0.0) || !std::isfinite(value))
      throw Error(std::string(name.value) + " " + std::to_string(value) + ": must be finite and >= 0");
    (s .* ... .* path) = value;
  };
  if (!row.result_key.empty()) row.replay = [](const nlohmann::ordered_json& v, RunControls& c) { c.*control = v.get<double>(); };
  return row;
}

}  // namespace thetad
