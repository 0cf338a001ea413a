// The run settings' table (settings/run_settings.hpp) walked row by row: each row's example
// changes a flight, the result records it and a replay flies it again; a scenario file says it
// under the row's file key to the same effect; the factors are its rows; and a result of an
// earlier format_version flies with the settings of its time.
#include "settings/run_settings.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "campaigns/factors.hpp"
#include "experiment/flight.hpp"
#include "experiment/provenance.hpp"
#include "experiment/replay.hpp"
#include "experiment/result_json.hpp"
#include "experiment/result_names.hpp"

namespace thetad {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using Json = nlohmann::ordered_json;

// A hover with a flight computer whose latency a slowdown may scale (the step time, given here).
constexpr const char* kSettingsTableScenario = R"(name: settings-table
duration: 4
initial_state:
  position: [0, 0, 2]
phases:
  - name: hold
    type: hold
    time: [0, 4]
simulation:
  computer:
    latency: step-time
    step_times: {lqr: 1.0e-5}
)";

Flight settings_table_flight(const RunControls& controls) {
  return Flight::from_text(kSettingsTableScenario, "settings-table.yaml", controls);
}

// What a result records of a flight before it flies: the settings and the provenance.
Json recorded_before_flying(const Flight& flight) {
  Json result;
  result["settings"] = settings_json(flight.settings());
  result["provenance"] = to_json(flight.provenance());
  return result;
}

// The row's example as a campaign file (or, for a seed, the command line) gives it.
RunControls example_controls(const RunSetting& setting) {
  RunControls controls;
  if (setting.parse)
    setting.parse(std::string(setting.example), controls);
  else
    setting.apply(factor_value(setting, std::string(setting.example)), controls);
  return controls;
}

TEST(RunSettings, EveryRowIsRecordedAndFliesAgainFromTheResult) {
  const Json plain = recorded_before_flying(settings_table_flight({}));
  for (const RunSetting& setting : run_settings()) {
    if (setting.value == RunSetting::Value::none) continue;
    SCOPED_TRACE(std::string(setting.name));
    ASSERT_FALSE(setting.example.empty());
    const Flight flown = settings_table_flight(example_controls(setting));
    const Json recorded = recorded_before_flying(flown);
    EXPECT_NE(recorded, plain) << "the example changes nothing a result records";
    const Flight again = settings_table_flight(recorded_controls(recorded, kRunFormatVersion));
    EXPECT_EQ(recorded_before_flying(again), recorded);
    EXPECT_EQ(again.initial_state(), flown.initial_state());
    EXPECT_EQ(again.scenario().duration, flown.scenario().duration);
  }
}

// kSettingsTableScenario with the row's example under its file key (the last of several), YAML's
// way: a switch as true or false.
std::string with_example_under_file_key(const RunSetting& setting) {
  const std::string keys(setting.file_key);
  std::vector<std::string> path;
  std::stringstream dotted(keys.substr(keys.rfind(' ') + 1));
  for (std::string key; std::getline(dotted, key, '.');) path.push_back(key);
  const std::string example = setting.value == RunSetting::Value::on_off ? (setting.example == "1" ? "true" : "false")
                                                                          : std::string(setting.example);
  YAML::Node root = YAML::Load(kSettingsTableScenario);
  YAML::Node node = root;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) node.reset(node[path[i]]);
  node[path.back()] = YAML::Load(example);
  YAML::Emitter text;
  text << root;
  return text.c_str();
}

// A file key means in a scenario file what the row means as a control: the parser reads it
// (scenarios/scenario.cpp) to the same settings.
TEST(RunSettings, EveryFileKeySaysInTheScenarioWhatTheControlSays) {
  for (const RunSetting& setting : run_settings()) {
    if (setting.file_key.empty() || setting.example.empty()) continue;
    SCOPED_TRACE(std::string(setting.name));
    const Flight from_file = Flight::from_text(with_example_under_file_key(setting), "settings-table.yaml", {});
    const Flight from_control = settings_table_flight(example_controls(setting));
    EXPECT_EQ(settings_json(from_file.settings()), settings_json(from_control.settings()));
  }
}

// The scenario parser reads every file key of the table: a row reads its own, or its key lies in a
// block that another row reads whole (the fields of simulation.wind: beyond_paper's).
TEST(RunSettings, TheScenarioParserReadsEveryFileKey) {
  std::vector<std::string> read_whole;
  for (const RunSetting& setting : run_settings()) {
    if (!setting.read) continue;
    std::stringstream keys{std::string(setting.file_key)};
    for (std::string key; std::getline(keys, key, ',');) read_whole.push_back(key.substr(key.find_first_not_of(' ')));
  }
  for (const RunSetting& setting : run_settings()) {
    if (setting.file_key.empty() || setting.read) continue;
    const std::string key(setting.file_key);
    EXPECT_TRUE(std::any_of(read_whole.begin(), read_whole.end(),
                            [&](const std::string& block) { return key.starts_with(block + "."); }))
        << setting.name << ": " << key;
  }
}

// The rows without a value of their own: the whole vectors and blocks a replay sets.
TEST(RunSettings, VectorsAndBlocksFlyAgainFromTheResult) {
  RunControls controls;
  controls.parameter_deviations = std::vector<double>(21, 0.5);
  controls.beyond_paper.servos = sim::ServoSettings{sim::InputVector::Constant(0.03), 1};
  controls.beyond_paper.discrete_gusts = std::vector<sim::DiscreteGust>{{1, 2.0, 0.5, 1.0}};
  const Json recorded = recorded_before_flying(settings_table_flight(controls));
  EXPECT_EQ(recorded["settings"]["parameter_deviations"].size(), 21u);
  EXPECT_EQ(recorded_before_flying(settings_table_flight(recorded_controls(recorded, kRunFormatVersion))), recorded);
}

TEST(RunSettings, NamesAreUniqueAndTheFactorsAreTheRowsWithAColumn) {
  std::set<std::string_view> names;
  for (const RunSetting& setting : run_settings()) {
    EXPECT_TRUE(names.insert(setting.name).second) << setting.name;
    if (!setting.earlier_name.empty()) {
      EXPECT_TRUE(names.insert(setting.earlier_name).second) << setting.earlier_name;
    }
    EXPECT_EQ(find_run_setting(setting.name), &setting);
    EXPECT_EQ(setting.is_factor(), find_factor(setting.name) != nullptr) << setting.name;
    // A value is set by apply, or parsed (a seed); an option reads a value the row can take.
    if (setting.value != RunSetting::Value::none) {
      EXPECT_TRUE(setting.apply || setting.parse) << setting.name;
    }
    if (setting.option_form != RunSetting::Option::none) {
      EXPECT_FALSE(setting.option.empty()) << setting.name;
    }
    // A row read back from results says from which version on they have it.
    if (!setting.result_key.empty()) {
      EXPECT_TRUE(setting.replay) << setting.name;
    }
    if (setting.before) {
      EXPECT_LT(setting.absent_until, kRunFormatVersion) << setting.name;
    }
  }
  // The runs table's factor columns, in the order the database versions added them.
  int column = 0;
  for (const Factor& factor : factors()) EXPECT_EQ(factor.factor_column, ++column) << factor.name;
  EXPECT_EQ(factors().front().name, "uncertainty_scale");
  EXPECT_EQ(factors().back().name, "duration_s");
  EXPECT_EQ(find_factor("servo_delay"), find_run_setting("servo_delay_samples"));
  EXPECT_EQ(find_factor("log_every"), nullptr);
}

// format_version 2 recorded no anti-windup: those runs flew without it, whatever the scenario
// says today; a result of version 3 must say it.
TEST(RunSettings, AnOlderResultFliesWithTheSettingsOfItsTime) {
  const fs::path fixture = fs::path(THETAD_SOURCE_DIR) / "tests/fixtures/results/hover-to-hover-theta-d-779336f.json";
  const Json version_2 = with_current_names(Json::parse(std::ifstream(fixture)));
  ASSERT_EQ(version_2["format_version"], 2);
  ASSERT_FALSE(version_2["settings"]["actuator_limits"].contains("anti_windup"));
  EXPECT_EQ(recorded_controls(version_2, 2).anti_windup, false);
  EXPECT_TRUE(Flight("hover-to-hover").settings().actuator_limits.anti_windup);

  const Replay replayed = replay(fixture);
  for (const std::string& difference : replayed.differences) ADD_FAILURE() << difference;
  EXPECT_EQ(replayed.largest_difference, 0.0);
  EXPECT_FALSE(replayed.result.summary.settings.actuator_limits.anti_windup);

  try {
    recorded_controls(version_2, 3);
    ADD_FAILURE() << "a version-3 result without the anti-windup was read";
  } catch (const Json::out_of_range& error) {
    EXPECT_THAT(error.what(), HasSubstr("anti_windup"));
  }

  // Version 1 files written before the scales and the actuator limits existed flew at the
  // paper's strengths, without limits.
  Json version_1 = version_2;
  version_1.erase("format_version");
  for (const char* key : {"uncertainty_scale", "gust_scale", "gust_onset_s", "actuator_limits"})
    version_1["settings"].erase(key);
  version_1["settings"]["noise"].erase("scale");
  const RunControls era = recorded_controls(version_1, 1);
  EXPECT_EQ(era.uncertainty_scale, 1.0);
  EXPECT_EQ(era.gust_scale, 1.0);
  EXPECT_EQ(era.gust_onset, 0.0);
  EXPECT_EQ(era.noise_scale, 1.0);
  EXPECT_EQ(era.actuator_limits, false);
  EXPECT_EQ(era.anti_windup, false);
  EXPECT_THROW(recorded_controls(version_1, 2), Json::out_of_range);
}

}  // namespace
}  // namespace thetad
