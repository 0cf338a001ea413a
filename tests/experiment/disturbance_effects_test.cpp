// Which disturbance does what (experiment/disturbance_effects): the sources a flight has on, the
// cases that tell them apart, and flights that are the ones a user would fly by hand.

#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "experiment/disturbance_effects.hpp"
#include "experiment/flight.hpp"

namespace {

using ::testing::ElementsAre;
using thetad::DisturbanceEffects;
using thetad::RunControls;

const std::string kHoverHold = THETAD_SOURCE_DIR "/scenarios/hover-hold.yaml";

std::vector<std::string> names(const std::vector<thetad::DisturbanceSource>& sources) {
  std::vector<std::string> result;
  for (const auto& source : sources) result.push_back(source.name);
  return result;
}

thetad::ControllerSpec spec(const std::string& label, const std::string& controller) {
  thetad::ControllerSpec result;
  result.label = label;
  result.controller = controller;
  return result;
}

RunControls short_flight() {
  RunControls controls;
  controls.duration = 2.0;
  return controls;
}

// The summary of `controller` flown by hand with `controls` (summary only, no timing, as the study flies).
thetad::sim::RunSummary fly(RunControls controls, const std::string& controller) {
  controls.summary_only = true;
  controls.timing = false;
  const thetad::Flight flight(kHoverHold, controls);
  thetad::PreparedController prepared = flight.prepare(spec(controller, controller));
  return flight.fly(prepared).summary;
}

const thetad::sim::RunSummary& run_of(const DisturbanceEffects& effects, const std::string& case_name) {
  for (const auto& run : effects.runs)
    if (run.case_name == case_name) return run.summary;
  throw std::runtime_error("no case " + case_name);
}

TEST(DisturbanceSources, ThePapersSettingHasItsSixAndIdealNone) {
  EXPECT_THAT(names(thetad::active_sources(thetad::sim::SimulationSettings::paper())),
              ElementsAre("parameter_uncertainty", "wind_gust", "measurement_noise", "actuator_noise", "wind_noise",
                          "induced_velocity_noise"));
  EXPECT_TRUE(thetad::active_sources(thetad::sim::SimulationSettings::ideal()).empty());
}

TEST(DisturbanceSources, ASourceScaledToZeroIsOffAndTheOnesBeyondThePaperCount) {
  thetad::sim::SimulationSettings settings = thetad::sim::SimulationSettings::ideal();
  settings.parameter_uncertainty = true;
  settings.uncertainty_scale = 0.0;
  settings.turbulence.model = thetad::sim::TurbulenceSettings::Model::dryden;
  settings.discrete_gusts.push_back({});
  settings.sensor_noise.bias[0] = 0.1;
  settings.servos.delay_samples = 2;
  EXPECT_THAT(names(thetad::active_sources(settings)),
              ElementsAre("turbulence", "discrete_gusts", "sensor_noise", "servos"));
}

TEST(DisturbanceCases, NoneEachAloneAllAndAllButEach) {
  thetad::sim::SimulationSettings settings = thetad::sim::SimulationSettings::ideal();
  settings.parameter_uncertainty = true;
  settings.wind_gust.enabled = true;
  settings.servos.delay_samples = 1;
  const auto cases = thetad::disturbance_cases(thetad::active_sources(settings), {});
  std::vector<std::string> case_names;
  for (const auto& c : cases) case_names.push_back(c.name);
  EXPECT_THAT(case_names, ElementsAre("none", "only parameter_uncertainty", "only wind_gust", "only servos", "all",
                                      "all but parameter_uncertainty", "all but wind_gust", "all but servos"));
  EXPECT_TRUE(cases[0].sources_on.empty());
  EXPECT_THAT(cases[6].sources_on, ElementsAre("parameter_uncertainty", "servos"));
  EXPECT_EQ(cases[6].controls.wind_gust, false);
  EXPECT_FALSE(cases[6].controls.parameter_uncertainty.has_value());
  EXPECT_EQ(cases[0].controls.servo_delay_samples, 0);

  settings.wind_gust.enabled = false;
  settings.servos.delay_samples = 0;
  const auto single = thetad::disturbance_cases(thetad::active_sources(settings), {});
  ASSERT_EQ(single.size(), 2u);
  EXPECT_EQ(single[1].name, "all");
}

TEST(DisturbanceEffects, EachCaseIsTheFlightAUserWouldFlyByHand) {
  RunControls controls = short_flight();
  controls.turbulence_model = thetad::sim::TurbulenceSettings::Model::dryden;
  const DisturbanceEffects effects = thetad::fly_disturbance_effects(kHoverHold, controls, {spec("lqr", "lqr")}, 2);
  ASSERT_EQ(effects.sources.size(), 7u);
  ASSERT_EQ(effects.runs.size(), effects.cases.size());

  // All on: the scenario as it is; none: ideal, with the scenario's actuator limits kept.
  EXPECT_EQ(run_of(effects, "all").cost, fly(controls, "lqr").cost);
  RunControls ideal = short_flight();
  ideal.ideal = true;
  ideal.actuator_limits = fly(short_flight(), "lqr").settings.actuator_limits.enabled;
  EXPECT_EQ(run_of(effects, "none").cost, fly(ideal, "lqr").cost);
  // The turbulence alone: ideal plus the turbulence.
  ideal.turbulence_model = controls.turbulence_model;
  EXPECT_EQ(run_of(effects, "only turbulence").cost, fly(ideal, "lqr").cost);
  // Each source changes the flight it is taken out of.
  for (const std::string& source : effects.sources) {
    if (source == "wind_noise") continue;  // the wind components' noise rides on the gust (docs/robustness.md)
    EXPECT_NE(run_of(effects, "all but " + source).cost, run_of(effects, "all").cost) << source;
  }
}

TEST(DisturbanceEffects, AFlightWithNoDisturbanceIsRefusedBeforeAnythingFlies) {
  RunControls controls = short_flight();
  controls.ideal = true;
  EXPECT_THROW(
      {
        try {
          thetad::fly_disturbance_effects(kHoverHold, controls, {spec("lqr", "lqr")}, 1);
        } catch (const thetad::Error& error) {
          EXPECT_THAT(error.what(), ::testing::HasSubstr("flies no disturbance"));
          throw;
        }
      },
      thetad::Error);
}

TEST(DisturbanceEffects, TheJsonNamesEveryRunByControllerAndCase) {
  const DisturbanceEffects effects =
      thetad::fly_disturbance_effects(kHoverHold, short_flight(), {spec("a", "lqr"), spec("b", "theta-d")}, 2);
  const auto json = thetad::disturbance_json(effects);
  EXPECT_EQ(json["format"], "thetad-disturbances");
  ASSERT_EQ(json["runs"].size(), 2 * effects.cases.size());
  EXPECT_EQ(json["runs"][1]["label"], "b");
  EXPECT_EQ(json["runs"][1]["controller"], "theta-d");
  EXPECT_EQ(json["runs"][1]["case"], "none");
  EXPECT_EQ(json["runs"][2]["case"], "only parameter_uncertainty");
  EXPECT_GT(json["runs"][2]["rms_error_m"].get<double>(), 0.0);
  EXPECT_EQ(json["seed"], effects.provenance.seed);
  EXPECT_TRUE(json["provenance"].contains("git_revision"));
  EXPECT_EQ(json["runs"][0]["settings"]["parameter_uncertainty"], false);
  EXPECT_EQ(json["runs"][2]["settings"]["parameter_uncertainty"], true);
  const std::string table = thetad::disturbance_table(effects);
  EXPECT_THAT(table, ::testing::HasSubstr("all but wind_gust"));
  EXPECT_THAT(table, ::testing::HasSubstr("J_dev"));
}

}  // namespace
