// The scenario's `simulation.computer` block (docs/model.md §15.7): what reaches the settings, and
// each mistake refused naming the field.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "settings/disturbance_blocks.hpp"
#include "scenarios/scenario.hpp"
#include "tests/error_message.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;
using thetad::testing::error_message;
using Computer = sim::FlightComputerSettings;

const std::string kHoldThenComputer = "name: test\nduration: 5\nphases:\n  - {name: hold, type: hold, time: [0, 5]}\nsimulation:\n";

Scenario scenario_of(const std::string& simulation) { return parse_scenario(kHoldThenComputer + simulation, "dir/test.yaml"); }

std::string computer_error_of(const std::string& simulation) {
  return error_message([&] { scenario_of(simulation); });
}

TEST(ComputerBlock, AbsentLeavesTheComputerOutOfTheLoop) {
  EXPECT_FALSE(scenario_of("  seed: 4\n").simulation_settings().computer.active());
}

TEST(ComputerBlock, FixedLatencyAndOverrunReachTheSettings) {
  const sim::SimulationSettings settings =
      scenario_of("  computer: {latency: fixed, fixed: 0.0004, overrun: abort}\n").simulation_settings();
  EXPECT_EQ(settings.computer.latency, Computer::Latency::fixed);
  EXPECT_EQ(settings.computer.fixed, 0.0004);
  EXPECT_EQ(settings.computer.overrun, Computer::Overrun::abort);
}

TEST(ComputerBlock, StepTimesByLabelOrABenchFileResolvedNextToTheScenario) {
  const sim::SimulationSettings given =
      scenario_of("  computer: {latency: step-time, slowdown: 30, step_times: {theta-d: 2e-6, sdre: 5e-5}}\n")
          .simulation_settings();
  EXPECT_EQ(given.computer.slowdown, 30.0);
  ASSERT_EQ(given.computer.step_times.size(), 2u);
  EXPECT_EQ(given.computer.step_time_of("sdre"), 5e-5);
  EXPECT_THAT(error_message([&] { given.computer.step_time_of("lqr"); }), HasSubstr("theta-d, sdre"));

  const Scenario from_file = scenario_of("  computer: {latency: step-time, bench: ../b/bench.json, statistic: p99}\n");
  ASSERT_TRUE(from_file.simulation.beyond_paper.step_time_file);
  EXPECT_EQ(from_file.simulation.beyond_paper.step_time_file->file, std::filesystem::path("dir/../b/bench.json"));
  EXPECT_EQ(from_file.simulation.beyond_paper.step_time_file->statistic, "p99");
}

TEST(ComputerBlock, MistakesAreRefusedNamingTheField) {
  EXPECT_THAT(computer_error_of("  computer: {latency: fixed}\n"), HasSubstr("simulation.computer.fixed"));
  EXPECT_THAT(computer_error_of("  computer: {latency: fixed, fixed: 0.001, slowdown: 3}\n"),
              HasSubstr("simulation.computer.slowdown"));
  EXPECT_THAT(computer_error_of("  computer: {latency: measured, fixed: 0.001}\n"), HasSubstr("only with latency: fixed"));
  EXPECT_THAT(computer_error_of("  computer: {latency: step-time}\n"), HasSubstr("simulation.computer.bench"));
  EXPECT_THAT(computer_error_of("  computer: {latency: step-time, bench: b.json, step_times: {a: 1e-6}}\n"),
              HasSubstr("one of them"));
  EXPECT_THAT(computer_error_of("  computer: {latency: step-time, bench: b.json, statistic: p95}\n"),
              HasSubstr("simulation.computer.statistic"));
  EXPECT_THAT(computer_error_of("  computer: {latency: step-time, step_times: {a: -1}}\n"),
              HasSubstr("simulation.computer.step_times.a"));
  EXPECT_THAT(computer_error_of("  computer: {latency: slow}\n"), HasSubstr("simulation.computer.latency"));
  EXPECT_THAT(computer_error_of("  computer: {latency: measured, slowdown: 0}\n"), HasSubstr("simulation.computer.slowdown"));
  EXPECT_THAT(computer_error_of("  computer: {latency: fixed, fixed: 0.001, jitter: 1}\n"), HasSubstr("jitter"));
}

}  // namespace
}  // namespace thetad
