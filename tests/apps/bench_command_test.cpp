// thetad bench as a user runs it: the per-step table and JSON for labelled controllers (plug-ins
// included), and clear errors for what cannot be timed.

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using thetad::testing::Output;

class BenchCommand : public ::testing::Test {
 protected:
  Output thetad(const std::string& arguments) const { return thetad::testing::run_thetad(dir_, arguments); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  thetad::testing::ScratchDirectory scratch_{"thetad_bench_command_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(BenchCommand, TimesEachLabelledControllerOnRecordedStates) {
  const Output output = thetad("bench --scenario scenario-1 --duration 2 --controllers paper=theta-d,lqr,pid=example-pid"
                               " --samples 200 --segments 4 --repetitions 2 --out " + path("bench.json"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("states recorded along 2 s flown by paper"));
  EXPECT_THAT(output.out, HasSubstr("median us"));
  EXPECT_THAT(output.out, HasSubstr("\npaper "));
  EXPECT_THAT(output.out, HasSubstr("\npid "));
  EXPECT_THAT(output.out, HasSubstr("one core at the period"));
  EXPECT_THAT(output.out, HasSubstr("Host: "));
  const auto j = nlohmann::json::parse(thetad::testing::read_text(dir_ / "bench.json"));
  EXPECT_EQ(j["format_version"], 2);
  EXPECT_EQ(j["recording_status"], "completed");
  EXPECT_EQ(j["recording_reason"], "");
  EXPECT_EQ(j["timed_steps_per_pass"], 200);
  // At least the passes asked for; more, up to three times as many, until the medians settle.
  const int repetitions = j["repetitions"];
  EXPECT_GE(repetitions, 2);
  EXPECT_LE(repetitions, 6);
  EXPECT_TRUE(j["medians_stable"].get<bool>() || repetitions == 6);
  for (const char* field : {"cpu_model", "governor", "load_average_before", "steal_share", "other_cores_busy_share",
                            "own_wait_share", "loaded", "warnings"})
    EXPECT_TRUE(j["host"].contains(field)) << field;
  ASSERT_EQ(j["controllers"].size(), 3u);
  for (const auto& c : j["controllers"]) {
    EXPECT_EQ(c["calls"], 200 * repetitions);
    EXPECT_TRUE(c.contains("verdict"));
    EXPECT_LE(c["step_time_p10_us"].get<double>(), c["step_time_median_us"].get<double>());
    EXPECT_LE(c["step_time_median_us"].get<double>(), c["step_time_p90_us"].get<double>());
    EXPECT_LE(c["step_time_p90_us"].get<double>(), c["step_time_p99_us"].get<double>());
    EXPECT_LE(c["step_time_p99_us"].get<double>(), c["step_time_max_us"].get<double>());
    EXPECT_GT(c["step_time_median_us"].get<double>(), 0.0);
  }
  EXPECT_EQ(j["controllers"][0]["label"], "paper");
  EXPECT_EQ(j["controllers"][0]["controller"], "theta-d");
  EXPECT_EQ(j["provenance"]["scenario"]["name"], "scenario-1");
}

// It writes no run, so the switches of a run's files are refused, not accepted and ignored.
TEST_F(BenchCommand, RefusesTheSwitchesOfARunsFiles) {
  for (const char* option : {"--no-timing", "--summary-only", "--log-every 5"}) {
    const Output output = thetad(std::string("bench --controllers lqr --duration 1 ") + option);
    EXPECT_EQ(output.status, 1) << option;
    EXPECT_THAT(output.err, HasSubstr("--")) << option;
  }
}

TEST_F(BenchCommand, TooShortAFlightForTheSamplesIsAClearError) {
  const Output output = thetad("bench --duration 0.1 --controllers lqr --samples 1000");
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("the flight recorded 100 samples, fewer than the 1100"));
}

}  // namespace
