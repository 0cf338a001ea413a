#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/sim/simulation_settings.hpp"
#include "settings/run_controls.hpp"
#include "settings/settings.hpp"

namespace thetad {

// Where a row's field is in a scenario file, for its reader: the block that holds it (the last of
// the row's file keys), the key in that block, and the file's folder (against which a file that the
// field names is resolved).
struct FileField {
  const Settings& block;
  std::string key;
  std::filesystem::path folder;
};

// The run settings: every condition a front end may set about a flight (RunControls), and what a
// result's "settings" records of the flight, described once. Each row says its name, where a
// scenario file, the command line, a campaign and a result have it, its range, and how it moves
// between them. The walkers below, apply(RunControls, SimulationSettings), the scenario parser
// (scenarios/simulation_block.hpp), the command line (add_flight_options), the campaign factors
// (campaigns/factors.hpp) and Python's keywords read the table. docs/scenarios.md "Adding a run
// condition" says what a new row needs.
struct RunSetting {
  // How a value is given (a campaign file, --set, the command line, Python).
  enum class Value {
    none,    // not by a value: a vector or block (set as a whole by a replay), a record only, or a
             // family of factors, each set by its own name (apply_named)
    number,  // a finite double in [min, max]
    whole,   // a whole number in [min, max]
    choice,  // one of `choices` by name, or its position
    on_off,  // a switch: 0 off, 1 on (a campaign file), on|off or a flag (the command line), a bool (Python)
    seed,    // a whole decimal from 0 to 2^64 - 1 (sim::parse_seed): never a double
  };
  // Its own command-line option, and how that reads: a value; on|off; on (off) when given.
  enum class Option { none, value, on_off, on_when_given, off_when_given };
  static constexpr int kEveryVersion = std::numeric_limits<int>::max();

  std::string_view name = {};  // the Python keyword, the campaign factor and its column, the docs' name
  Value value = Value::none;
  std::string_view unit = {};
  std::string_view description = {};  // for docs and --help
  double min = -std::numeric_limits<double>::infinity(), max = std::numeric_limits<double>::infinity();
  // A choice's names, space-separated; a campaign file may write a name for its position (0, 1, ...).
  std::string_view choices = {};
  // Sets it in RunControls: a number (a switch 0 or 1, a choice its position). Seeds: parse.
  void (*apply)(double value, RunControls& controls) = nullptr;
  void (*parse)(const std::string& text, RunControls& controls) = nullptr;
  // Its column among the campaign factors (1 the first; the runs table's order, which the database
  // versions fixed); 0: not a factor.
  int factor_column = 0;
  // A family of factors instead, one per name after the prefix of `name` ("plant.NAME": plant.epsilon
  // and any other plant setting; "initial_state.I": initial_state.0, ...), each a finite number,
  // set by its whole name. They have no column of their own: a campaign's database gives each one
  // it names a column of that name (docs/campaigns.md).
  void (*apply_named)(std::string_view name, double value, RunControls& controls) = nullptr;
  // Its name before docs/glossary.md, which campaign files and Python still take.
  std::string_view earlier_name = {};
  // A value, as a campaign file writes it, that changes a helicopter flight from thetad's defaults
  // (for docs and the table's test).
  std::string_view example = {};

  std::string_view option = {};  // "--dt"
  Option option_form = Option::none;
  bool option_writes_runs = false;  // offered only by the commands that write run files

  // What it does to the flight's settings when given (after the scenario's, in table order).
  // Controls that act on the scenario or the initial state have none: Flight applies them.
  void (*fly)(const RunControls& controls, sim::SimulationSettings& settings) = nullptr;

  // Its part of a result's "settings" (a field, or a block holding the fields of other rows),
  // written in table order; none when another row's block or the provenance records it.
  void (*record)(const sim::SimulationSettings& settings, nlohmann::ordered_json& json) = nullptr;
  // Where a result has it (dotted, under the current names: "settings.noise.scale",
  // "provenance.seed"), read back by `replay`; empty: replayed with a block.
  std::string_view result_key = {};
  void (*replay)(const nlohmann::ordered_json& recorded, RunControls& controls) = nullptr;
  // Results of format_version <= absent_until may lack it: they flew as `before` sets (the setting
  // as it was before results recorded it; nullptr: not given, so the scenario's). 0: every result
  // has it; kEveryVersion: recorded only when given.
  int absent_until = 0;
  void (*before)(RunControls& controls) = nullptr;

  // Where a scenario file says it (docs/scenarios.md), dotted, several keys separated by ", ";
  // empty: only a run control. `read` takes it from the file into the file's RunControls (given the
  // block of the last key, present or not); a row without one documents a field that another row's
  // block reads (the fields of `simulation.wind`: beyond_paper's).
  std::string_view file_key = {};
  void (*read)(const FileField& field, RunControls& controls) = nullptr;

  bool is_family() const { return apply_named != nullptr; }
  bool is_factor() const { return factor_column > 0 || is_family(); }
  // Whether `factor` is this row's name or, for a family, one of its members.
  bool names(std::string_view factor) const;
  // The factor `given` (one it names) under its current name: the row's (duration_s for duration),
  // or a family member's own (plant.epsilon).
  std::string current_name(std::string_view given) const { return std::string(is_family() ? given : name); }
  // Sets the factor `factor` (this row's name, or a member of its family) to `value`.
  void set(std::string_view factor, double value, RunControls& controls) const;
};

// Every run setting, in the order they act on a flight's settings and a result records them.
const std::vector<RunSetting>& run_settings();
// The setting named `name` (or by its earlier name); nullptr when there is none.
const RunSetting* find_run_setting(std::string_view name);

// What a scenario file's `simulation` block says about its flight: every row's field read by the
// row, from the block its file key names (`simulation` or `simulation.disturbances`). Those blocks
// may hold the rows' fields and, in `simulation`, `scenario_fields` (what the scenario itself reads:
// `model`); `folder` is the file's. Throws SettingsError naming the field and the reason.
RunControls read_simulation_block(const Settings& simulation, const std::filesystem::path& folder,
                                  std::initializer_list<std::string_view> scenario_fields);

// A result's "settings": every row's record, in table order.
nlohmann::ordered_json settings_json(const sim::SimulationSettings& settings);

// The controls a result (under the current names, with_current_names) of format_version `version`
// flew with: every row with a result key read back, or set as it was before results of its version
// recorded it. Throws nlohmann's out_of_range naming a field the version must have.
RunControls recorded_controls(const nlohmann::ordered_json& result, int version);

}  // namespace thetad
