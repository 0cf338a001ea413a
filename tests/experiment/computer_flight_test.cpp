// The flight computer through a Flight (docs/model.md §15.7): step times read from a bench file next
// to the scenario, taken by the controller's label, recorded in the result with the file's digest,
// and replayed without the file; the slowdown control.
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "experiment/flight.hpp"
#include "experiment/replay.hpp"
#include "experiment/run_files.hpp"
#include "experiment/sha256.hpp"
#include "tests/error_message.hpp"
#include "tests/scratch_directory.hpp"

namespace thetad {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using thetad::testing::error_message;

class ComputerFlight : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "bench.json")
        << R"({"format": "thetad-bench-1", "format_version": 2, "controllers": [)"
           R"({"label": "lqr", "step_time_median_us": 50.0, "step_time_p99_us": 400.0}]})";
    std::ofstream(dir_ / "hold.yaml")
        << "name: hold\nduration: 1\ninitial_state: {position: [0, 0, 3.5]}\n"
           "phases:\n  - {name: hold, type: hold, time: [0, 1]}\n"
           "simulation:\n  computer: {latency: step-time, bench: bench.json, statistic: p99, slowdown: 3}\n";
  }

  RunControls controls(double duration) const {
    RunControls c;
    c.duration = duration;
    c.timing = false;
    return c;
  }

  testing::ScratchDirectory scratch_{"thetad_computer_flight_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(ComputerFlight, StepTimesComeFromTheBenchFileByLabelAndTheResultReplaysWithoutIt) {
  const Flight flight((dir_ / "hold.yaml").string(), controls(0.2));
  const sim::FlightComputerSettings computer = flight.flown_settings("lqr").computer;
  EXPECT_DOUBLE_EQ(computer.step_time, 400e-6);
  EXPECT_THAT(computer.step_time_source, HasSubstr(sha256_of_file(dir_ / "bench.json")));
  EXPECT_THAT(computer.step_time_source, HasSubstr("p99"));
  PreparedController lqr = flight.prepare(parse_controller_spec("lqr"));
  const RunResult run = flight.fly(lqr);
  ASSERT_TRUE(run.summary.computer);
  EXPECT_NEAR(run.summary.computer->max_latency, 1.2e-3, 1e-15);  // 3 × 400 µs: past the 1 ms period
  EXPECT_GT(run.summary.computer->missed_deadlines, 0);
  EXPECT_GT(run.summary.computer->skipped_samples, 0);

  const RunFiles files = write_run_files(run, dir_ / "out");
  fs::remove(dir_ / "bench.json");
  const Replay again = replay(files.json);
  EXPECT_TRUE(again.differences.empty()) << again.differences.front();
  EXPECT_EQ(again.result.summary.computer->missed_deadlines, run.summary.computer->missed_deadlines);
}

TEST_F(ComputerFlight, AControllerTheBenchFileDidNotTimeIsRefusedBeforeAnyFlight) {
  const Flight flight((dir_ / "hold.yaml").string(), controls(0.2));
  const std::string message = error_message([&] { flight.prepare(parse_controller_spec("theta-d")); });
  EXPECT_THAT(message, HasSubstr("no step time for controller theta-d"));
  EXPECT_THAT(message, HasSubstr("gives lqr"));
}

TEST_F(ComputerFlight, TheSlowdownControlScalesTheStepTimesAndNeedsAComputerThatUsesThem) {
  RunControls faster = controls(0.2);
  faster.slowdown = 0.5;
  const Flight flight((dir_ / "hold.yaml").string(), faster);
  PreparedController lqr = flight.prepare(parse_controller_spec("lqr"));
  const RunResult run = flight.fly(lqr);
  EXPECT_NEAR(run.summary.computer->max_latency, 0.2e-3, 1e-15);
  EXPECT_EQ(run.summary.computer->missed_deadlines, 0);
  EXPECT_EQ(run.summary.computer->skipped_samples, 0);

  RunControls slowdown = controls(0.2);
  slowdown.slowdown = 2.0;
  EXPECT_THAT(error_message([&] { Flight(THETAD_SOURCE_DIR "/scenarios/hover-hold.yaml", slowdown); }),
              HasSubstr("slowdown: only for a flight computer"));
}

TEST_F(ComputerFlight, AMissingOrForeignBenchFileIsAnErrorNamingIt) {
  fs::remove(dir_ / "bench.json");
  EXPECT_THAT(error_message([&] { Flight((dir_ / "hold.yaml").string(), controls(0.2)); }), HasSubstr("bench.json"));
  std::ofstream(dir_ / "bench.json") << R"({"format": "thetad-run-1"})";
  EXPECT_THAT(error_message([&] { Flight((dir_ / "hold.yaml").string(), controls(0.2)); }),
              HasSubstr("not a thetad bench file"));
}

// The study's scenario flies with the bench file shipped beside it, which times each of the
// campaign's controllers.
TEST(ComputerStudy, TheShippedScenarioHasAStepTimeForEachControllerOfItsCampaign) {
  RunControls controls;
  controls.duration = 0.05;
  controls.timing = false;
  const Flight flight(THETAD_SOURCE_DIR "/scenarios/computer/scenario-1-onboard.yaml", controls);
  for (const char* label : {"theta-d", "sdre", "sdre-cold"}) EXPECT_GT(flight.flown_settings(label).computer.step_time, 0.0);
  PreparedController theta_d = flight.prepare(parse_controller_spec("theta-d"));
  EXPECT_EQ(flight.fly(theta_d).summary.status, sim::RunStatus::completed);
}

}  // namespace
}  // namespace thetad
