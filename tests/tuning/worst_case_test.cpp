// Worst cases of Table 1's parameter bounds (tuning/worst_case): fixed deviations reach the plant,
// the search stays in the box and its budget and finds a flight at least as bad as the nominal one,
// and the scenario file it writes flies the worst case again, bit for bit.

#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/helicopter/uncertainty.hpp"
#include "experiment/flight.hpp"
#include "experiment/replay.hpp"
#include "experiment/run_files.hpp"
#include "tests/scratch_directory.hpp"
#include "tuning/worst_case.hpp"

namespace thetad::tuning {
namespace {

const std::string kHoverHold = THETAD_SOURCE_DIR "/scenarios/hover-hold.yaml";

ControllerSpec spec(const std::string& name) {
  ControllerSpec result;
  result.label = result.controller = name;
  return result;
}

RunControls one_quiet_second() {
  RunControls controls;
  controls.duration = 1.0;
  controls.summary_only = true;
  controls.timing = false;
  return controls;
}

TEST(ParameterDeviations, ReplaceTheDrawAndMustLieInTheBox) {
  RunControls controls = one_quiet_second();
  controls.parameter_deviations = std::vector<double>(21, 1.0);
  const Flight flight(kHoverHold, controls);
  PreparedController lqr = flight.prepare(spec("lqr"));
  const sim::RunSummary summary = flight.fly(lqr).summary;
  const auto worst = heli::worst_case_parameters(heli::Parameters{});
  ASSERT_EQ(summary.parameter_factors.size(), 21u);
  std::size_t i = 0;
  for (const auto& row : worst.report) {
    if (row.per_sample) continue;
    EXPECT_EQ(summary.parameter_factors[i].first, row.name);
    EXPECT_EQ(summary.parameter_factors[i++].second, row.factor) << row.name;
  }
  // The result records them and a replay flies them again.
  const thetad::testing::ScratchDirectory scratch("thetad_worst_case_test");
  const RunResult result = flight.fly(lqr);
  const RunFiles files = write_run_files(result, scratch.path());
  const Replay again = replay(files.json);
  EXPECT_TRUE(again.differences.empty()) << again.differences.front();
  EXPECT_EQ(again.result.summary.parameter_factors, summary.parameter_factors);

  controls.parameter_deviations = std::vector<double>(21, 0.0);
  controls.parameter_deviations->at(3) = 2.0;
  EXPECT_THROW(Flight(kHoverHold, controls), Error);
  controls.parameter_deviations = std::vector<double>(20, 0.0);
  EXPECT_THROW(Flight(kHoverHold, controls), Error);
}

TEST(WorstCase, FindsAFlightAtLeastAsBadAsTheNominalWithinItsBudgetAndFliesItAgain) {
  WorstCaseOptions options;
  options.corners = 4;
  options.max_evaluations = 60;  // the design's 47, then the search
  options.threads = 2;
  int reported = 0;
  options.progress = [&](const std::string&, int evaluations, int budget) {
    EXPECT_LE(evaluations, budget);
    reported = evaluations;
  };
  const WorstCases cases = find_worst_cases(kHoverHold, one_quiet_second(), {spec("lqr")}, options);
  ASSERT_EQ(cases.controllers.size(), 1u);
  const WorstCase& lqr = cases.controllers[0];
  EXPECT_EQ(lqr.evaluations, reported);
  EXPECT_LE(lqr.evaluations, options.max_evaluations);
  EXPECT_GT(lqr.evaluations, 47);
  EXPECT_THAT(lqr.stop, ::testing::HasSubstr("NLopt"));
  EXPECT_THAT(lqr.nominal.xi, ::testing::Each(0.0));
  EXPECT_GT(lqr.worst.value, lqr.nominal.value);
  for (const double x : lqr.worst.xi) EXPECT_LE(std::abs(x), 1.0);
  EXPECT_EQ(lqr.worst.value, lqr.worst.summary.rms_tracking_error.norm());

  const std::string file = worst_case_scenario(cases.provenance.scenario_text, lqr.worst);
  const Flight again = Flight::from_text(file, "worst.yaml", {});
  EXPECT_EQ(again.settings().parameter_deviations, lqr.worst.xi);
  PreparedController controller = again.prepare(spec("lqr"));
  const sim::RunSummary replayed = again.fly(controller).summary;
  EXPECT_EQ(replayed.cost, lqr.worst.summary.cost);
  EXPECT_EQ(replayed.rms_tracking_error, lqr.worst.summary.rms_tracking_error);

  const auto json = worst_case_json(cases);
  EXPECT_EQ(json["metric"], "rms_error_m");
  EXPECT_EQ(json["controllers"][0]["worst"]["rms_error_m"].get<double>(), lqr.worst.value);
  EXPECT_EQ(json["controllers"][0]["worst"]["parameter_deviations"].size(), 21u);
}

TEST(WorstCase, ABudgetTheDesignSpendsEndsThere) {
  WorstCaseOptions options;
  options.corners = 0;
  options.max_evaluations = 5;
  options.metric = WorstCaseMetric::cost_dev;
  const WorstCases cases = find_worst_cases(kHoverHold, one_quiet_second(), {spec("lqr")}, options);
  EXPECT_EQ(cases.controllers[0].evaluations, 5);
  EXPECT_EQ(cases.controllers[0].stop, "the budget went to the sampled design");
  EXPECT_EQ(cases.controllers[0].worst.value, *cases.controllers[0].worst.summary.cost_dev);
}

}  // namespace
}  // namespace thetad::tuning
