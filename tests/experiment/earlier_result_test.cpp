// Results written by earlier builds fly again to the same figures and read under the current names
// (docs/glossary.md; experiment/result_json.hpp lists the versions). The fixtures
// (tests/fixtures/results) are files as those builds wrote them:
//   - hover-to-hover-theta-d-779336f.json, format_version 2, by thetad at 779336f, before the
//     feed-forward settings and J_dev existed (hover-to-hover, θ–D, seed 1, 2 s, summary-only). Its
//     settings leave feedforward out, which is `none`, and it recorded the scenario's text, so an
//     edit of the shipped file does not change the replay.
//   - hover-to-hover-theta-d-format-3/, format_version 3, by thetad at b596be7, the last version
//     with the grouped figures (tracking_error_m, control_effort, saturation, cost.J, cost_dev.J_dev,
//     compute_time_ns in ns) and the log column compute_ns (hover-to-hover, θ–D, seed 2, 0.2 s,
//     every 20th sample logged, timed).
//   - format_version 1, made here from the latter as version 1 wrote it: no format_version, no
//     log.columns, no scenario text (the scenario by its file and SHA-256).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "experiment/flight.hpp"
#include "experiment/replay.hpp"
#include "experiment/result_json.hpp"
#include "experiment/result_names.hpp"
#include "experiment/run_files.hpp"
#include "tests/error_message.hpp"
#include "tests/scratch_directory.hpp"

namespace thetad {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using Json = nlohmann::ordered_json;

const fs::path kFixtures = fs::path(THETAD_SOURCE_DIR) / "tests" / "fixtures" / "results";
const fs::path kVersion3 = kFixtures / "hover-to-hover-theta-d-format-3";

Json read_json(const fs::path& file) { return Json::parse(std::ifstream(file)); }

TEST(EarlierResult, FliesAgainToTheSameCost) {
  const Replay replayed = replay(kFixtures / "hover-to-hover-theta-d-779336f.json");
  constexpr double kRecordedJ = 7243.411607772617;
  EXPECT_LE(std::abs(replayed.result.summary.cost - kRecordedJ), 1e-9 * kRecordedJ);
  for (const std::string& difference : replayed.differences) ADD_FAILURE() << difference;
  EXPECT_TRUE(replayed.result.summary.cost_dev.has_value());
}

// Every figure of version 3 comes back under its current name, with its value; only what version
// 4 added is absent (the 3-D figures and the definitions). (Replay compares only what a file recorded: a figure lost here would
// go unchecked there.)
TEST(EarlierResult, Version3ReadsUnderTheCurrentNames) {
  const Json current = with_current_names(read_json(kVersion3 / "theta-d.json"));
  EXPECT_EQ(current["format_version"], 3);
  EXPECT_EQ(current["rms_error_x_m"].get<double>(), 0.0006450642234778479);
  EXPECT_EQ(current["rms_error_z_m"].get<double>(), 0.0002774394834540695);
  EXPECT_EQ(current["max_error_y_m"].get<double>(), 0.008035113000433287);
  EXPECT_EQ(current["rms_command_T_mr_N"].get<double>(), 80.38382027867843);
  EXPECT_EQ(current["rms_command_delta_lat_rad"].get<double>(), 0.017875901372832417);
  EXPECT_EQ(current["saturated_magnitude_T_mr"], 0);
  EXPECT_EQ(current["saturated_rate_T_mr"], 152);
  EXPECT_EQ(current["saturated_rate_delta_lat"], 26);
  EXPECT_EQ(current["saturated_samples"], 190);
  EXPECT_EQ(current["cost"].get<double>(), 659.3368505702687);
  EXPECT_EQ(current["cost_dev"].get<double>(), 4.185430968954117);
  EXPECT_THAT(current["cost_dev_weights"].get<std::string>(), HasSubstr("designed weights"));
  EXPECT_DOUBLE_EQ(current["in_flight_step_time_median_us"].get<double>(), 10.27);
  EXPECT_DOUBLE_EQ(current["in_flight_step_time_p99_us"].get<double>(), 12.853);
  EXPECT_EQ(current["wall_time_s"].get<double>(), 0.009486228);
  const Json& settings = current["settings"];
  EXPECT_TRUE(settings["timing"].get<bool>());
  EXPECT_FALSE(settings["summary_only"].get<bool>());
  EXPECT_EQ(settings["gust_scale"], 1.0);
  EXPECT_EQ(settings["gust_onset_s"], 0.0);
  EXPECT_EQ(current["log"]["columns"].back()["name"], "in_flight_step_time");
  for (const char* earlier : {"tracking_error_m", "control_effort", "saturation", "compute_time_ns", "wall_seconds"})
    EXPECT_FALSE(current.contains(earlier)) << earlier;
  for (const char* earlier : {"keep_log", "measure_compute_time"}) EXPECT_FALSE(settings.contains(earlier)) << earlier;
  EXPECT_FALSE(settings["wind_gust"].contains("amplitude_scale"));

  RunControls controls;
  controls.seed = 2;
  controls.duration = 0.2;
  controls.log_every = 20;
  const Flight flight("hover-to-hover", controls);
  PreparedController prepared = flight.prepare(parse_controller_spec("theta-d"));
  const Json now = summary_json(flight.fly(prepared).summary);
  for (const auto& [key, value] : now.items()) {
    const bool new_in_4 = key == "rms_error_m" || key == "max_axis_error_m" || key == "definitions";
    if (!new_in_4) {
      EXPECT_TRUE(current.contains(key)) << key;
    }
  }
}

TEST(EarlierResult, Version3FliesAgainAndItsFolderReadsAsTheCurrentOne) {
  const Replay replayed = replay(kVersion3 / "theta-d.json");
  for (const std::string& difference : replayed.differences) ADD_FAILURE() << difference;
  EXPECT_EQ(replayed.result.summary.cost, 659.3368505702687);
  EXPECT_EQ(replayed.result.summary.saturation.samples_limited, 190);
  EXPECT_EQ(replayed.result.summary.settings.log_every, 20);

  const std::vector<StoredRun> runs = read_result_folder(kVersion3);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].columns.back().header(), "in_flight_step_time_ns");
  EXPECT_EQ(runs[0].result["cost"].get<double>(), 659.3368505702687);
}

class EarlierFiles : public ::testing::Test {
 protected:
  testing::ScratchDirectory scratch_{"thetad_earlier_result_test"};
  const fs::path dir_ = scratch_.path();

  // The version-3 fixture as version 1 wrote it, its scenario in a file of its own.
  fs::path version_1() const {
    Json result = read_json(kVersion3 / "theta-d.json");
    result.erase("format_version");
    result["log"].erase("columns");
    Json& scenario = result["provenance"]["scenario"];
    std::ofstream(dir_ / "hover-to-hover.yaml", std::ios::binary) << scenario["text"].get<std::string>();
    scenario.erase("text");
    scenario["file"] = (dir_ / "hover-to-hover.yaml").string();
    std::ofstream(dir_ / "theta-d.json") << result.dump(2);
    fs::copy_file(kVersion3 / "theta-d.csv", dir_ / "theta-d.csv");
    return dir_ / "theta-d.json";
  }
};

// A result of format_version 1 replays from its scenario file, which must still be the bytes it
// flew; its log (header compute_ns then) reads under the current column name.
TEST_F(EarlierFiles, Version1ReplaysFromItsFileAndReadsUnderTheCurrentNames) {
  const fs::path file = version_1();
  const Replay replayed = replay(file);
  for (const std::string& difference : replayed.differences) ADD_FAILURE() << difference;
  EXPECT_EQ(replayed.result.summary.cost, 659.3368505702687);

  const std::vector<StoredRun> runs = read_result_folder(dir_);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].columns.back().header(), "in_flight_step_time_ns");
  EXPECT_EQ(runs[0].result["max_error_x_m"].get<double>(), 0.0016878327819127461);
  EXPECT_TRUE(runs[0].result["settings"]["timing"].get<bool>());

  std::ofstream(dir_ / "hover-to-hover.yaml", std::ios::app) << "# edited\n";
  EXPECT_THAT(testing::error_message([&] { replay(file); }), HasSubstr("has changed since the run"));
}

// A replay that differs names the figure under its current name.
TEST_F(EarlierFiles, AnEditedFigureOfAnEarlierResultIsADifference) {
  Json result = read_json(kVersion3 / "theta-d.json");
  result["saturation"]["rate"][1] = 155;
  std::ofstream(dir_ / "edited.json") << result.dump(2);
  fs::copy_file(kVersion3 / "theta-d.csv", dir_ / "theta-d.csv");
  const Replay replayed = replay(dir_ / "edited.json");
  ASSERT_EQ(replayed.differences.size(), 1u);
  EXPECT_THAT(replayed.differences[0], HasSubstr("saturated_rate_delta_ped: recorded 155, replayed 156"));
}

}  // namespace
}  // namespace thetad
