#include "scenarios/scenario.hpp"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;

const std::string kScenarios = std::string(THETAD_SOURCE_DIR) + "/scenarios/";

// The message of the thetad::Error that parsing `text` (named "test.yaml") throws.
std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "test.yaml");
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

// A valid two-phase file; the tests break one field at a time.
const std::string kHeader = "name: test\nduration: 12\nphases:\n";  // lines 1-3
const std::string kTakeoff = "  - name: takeoff\n    type: ramp\n    time: [0, 7]\n    to: [0, 0, 3.5]\n";  // 4-7
const std::string kHover = "  - name: hover\n    type: hold\n    time: [7, 12]\n";  // 8-10

TEST(Scenario, TheValidTestFileLoads) {
  const Scenario scenario = parse_scenario(kHeader + kTakeoff + kHover, "test.yaml");
  EXPECT_EQ(scenario.name, "test");
  EXPECT_EQ(scenario.duration, 12.0);
  EXPECT_EQ(scenario.trajectory.phases().size(), 2u);
  EXPECT_EQ(scenario.trajectory.position(12.0), Eigen::Vector3d(0.0, 0.0, -3.5));  // h = 3.5 -> z = -3.5
  // Default initial state: at rest on the ground, s = 1 (docs/model.md §8.1); the paper's disturbances.
  Eigen::VectorXd rest = Eigen::VectorXd::Zero(heli::kStateDim);
  rest(heli::kS) = 1.0;
  EXPECT_EQ(scenario.initial_state, rest);
  const sim::SimulationSettings settings = scenario.simulation_settings();
  EXPECT_EQ(settings.duration, 12.0);
  EXPECT_TRUE(settings.parameter_uncertainty);
  EXPECT_TRUE(settings.wind_gust.enabled);
  EXPECT_EQ(scenario.model_options, heli::ModelOptions::resolved());
}

TEST(Scenario, ScenarioOneIsTheSpecsTable) {
  const Scenario scenario = load_scenario(kScenarios + "scenario-1.yaml");
  EXPECT_EQ(scenario.name, "scenario-1");
  EXPECT_EQ(scenario.duration, 85.0);
  const auto& phases = scenario.trajectory.phases();
  ASSERT_EQ(phases.size(), 6u);
  const double boundaries[] = {0, 7, 12, 62, 72, 79, 85};
  for (std::size_t i = 0; i < phases.size(); ++i) {
    EXPECT_EQ(phases[i].start_time, boundaries[i]);
    EXPECT_EQ(phases[i].end_time, boundaries[i + 1]);
  }
  const auto& eight = std::get<FigureEight>(phases[2].motion);
  EXPECT_EQ(eight.amplitude_x, 8.0);
  EXPECT_EQ(eight.amplitude_y, 4.0);
  EXPECT_EQ(eight.period, 50.0);
  const Eigen::Vector3d hover(0.0, 0.0, -3.5);
  for (const double t : {7.0, 12.0, 62.0, 72.0}) EXPECT_LT((scenario.trajectory.position(t) - hover).norm(), 1e-12);
  EXPECT_LT(scenario.trajectory.position(12.1).y(), 0.0);  // first towards -y
  EXPECT_GT(scenario.trajectory.position(12.1).x(), 0.0);  // and +x
  EXPECT_EQ(scenario.trajectory.position(85.0), Eigen::Vector3d::Zero());
  EXPECT_FALSE(scenario.simulation.seed.has_value());
}

TEST(Scenario, ScenarioTwoIsTheSpecsTable) {
  const Scenario scenario = load_scenario(kScenarios + "scenario-2.yaml");
  EXPECT_EQ(scenario.duration, 82.0);
  const auto& phases = scenario.trajectory.phases();
  ASSERT_EQ(phases.size(), 4u);
  const auto& circle = std::get<Circle>(phases[2].motion);
  EXPECT_EQ(circle.radius, 15.0);
  EXPECT_EQ(circle.period, 60.0);
  EXPECT_EQ(circle.descent, 2.0);
  EXPECT_TRUE(circle.counterclockwise);
  EXPECT_EQ(phases[2].start_time, 12.0);
  EXPECT_EQ(phases[2].end_time, 72.0);
  EXPECT_LT((scenario.trajectory.position(42.0) - Eigen::Vector3d(0.0, 30.0, -1.5)).norm(), 1e-9);
}

TEST(Scenario, HoverStepAndFastForwardLoad) {
  const Scenario steps = load_scenario(kScenarios + "hover-step.yaml");
  EXPECT_EQ(steps.trajectory.position(44.0), Eigen::Vector3d(1.0, 1.0, -4.5));
  const Scenario fast = load_scenario(kScenarios + "fast-forward.yaml");
  EXPECT_EQ(fast.model_options.rotor_speed_model, heli::ModelOptions::RotorSpeedModel::governor);
  const double cruise_speed = (fast.trajectory.position(40.0) - fast.trajectory.position(39.0)).norm();
  EXPECT_NEAR(cruise_speed, 20.0, 1e-9);
  EXPECT_LT((fast.trajectory.position(77.0) - Eigen::Vector3d(700.0, 0.0, -3.5)).norm(), 1e-9);
}

TEST(Scenario, SimulationOverridesApply) {
  const Scenario scenario = parse_scenario(kHeader + kTakeoff + kHover +
                                               "simulation:\n  dt: 0.002\n  controller_period_steps: 2\n"
                                               "  seed: 18446744073709551615\n"
                                               "  disturbances:\n    wind_gust: off\n    measurement_noise: false\n"
                                               "  model:\n    preset: paper\n    yaw_inertia: izz\n",
                                           "test.yaml");
  const sim::SimulationSettings settings = scenario.simulation_settings();
  EXPECT_EQ(settings.dt, 0.002);
  EXPECT_EQ(settings.controller_period_steps, 2);
  EXPECT_EQ(settings.seed, 18446744073709551615u);  // the whole unsigned 64-bit range
  EXPECT_FALSE(settings.wind_gust.enabled);
  EXPECT_FALSE(settings.noise.measurement);
  EXPECT_TRUE(settings.noise.actuator);
  heli::ModelOptions expected = heli::ModelOptions::paper();
  expected.yaw_inertia = heli::ModelOptions::YawInertia::izz;
  EXPECT_EQ(scenario.model_options, expected);
  EXPECT_EQ(scenario.model_preset, "paper");
}

TEST(Scenario, ActuatorLimitsAreOnUnlessTurnedOffAndNeverFlyThePaperPresetUnasked) {
  const auto limits_on = [](const std::string& simulation, bool base_on) {
    sim::SimulationSettings base;
    base.actuator_limits.enabled = base_on;
    return parse_scenario(kHeader + kTakeoff + kHover + simulation, "test.yaml")
        .simulation_settings(base)
        .actuator_limits.enabled;
  };
  const auto limits_by_default = [](const std::string& simulation) {
    return parse_scenario(kHeader + kTakeoff + kHover + simulation, "test.yaml").simulation_settings().actuator_limits;
  };
  EXPECT_TRUE(sim::SimulationSettings{}.actuator_limits.enabled);
  EXPECT_FALSE(sim::SimulationSettings::paper().actuator_limits.enabled);
  EXPECT_FALSE(sim::SimulationSettings::ideal().actuator_limits.enabled);
  EXPECT_TRUE(limits_by_default("").enabled);
  EXPECT_EQ(limits_by_default("").upper, sim::ActuatorLimits::x_cell().upper);
  EXPECT_FALSE(limits_by_default("simulation:\n  actuator_limits: off\n").enabled);
  EXPECT_FALSE(limits_by_default("simulation:\n  model:\n    preset: paper\n").enabled);
  EXPECT_FALSE(limits_on("", false));
  EXPECT_TRUE(limits_on("simulation:\n  actuator_limits: on\n", false));
  EXPECT_TRUE(limits_on("", true));
  EXPECT_FALSE(limits_on("simulation:\n  model:\n    preset: paper\n", true));
  EXPECT_TRUE(limits_on("simulation:\n  actuator_limits: on\n  model:\n    preset: paper\n", false));
  EXPECT_FALSE(limits_on("simulation:\n  actuator_limits: off\n", true));
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  actuator_limits: maybe\n"),
              HasSubstr("field 'simulation.actuator_limits'"));
}

TEST(Scenario, RunControlsInTheSimulationBlock) {
  const Scenario scenario = parse_scenario(kHeader + kTakeoff + kHover +
                                               "simulation:\n  duration: 4.5\n  log_every: 10\n  summary_only: true\n"
                                               "  timing: false\n",
                                           "test.yaml");
  const sim::SimulationSettings settings = scenario.simulation_settings();
  EXPECT_EQ(settings.duration, 4.5);
  EXPECT_EQ(settings.log_every, 10);
  EXPECT_FALSE(settings.keep_log);
  EXPECT_FALSE(settings.measure_compute_time);
  EXPECT_EQ(scenario.model_preset, "resolved");
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  dt: 0.0003\n"),
              HasSubstr("field 'simulation.dt': 0.0003 s does not divide the controller period 0.001 s"));
  const sim::SimulationSettings half =
      parse_scenario(kHeader + kTakeoff + kHover + "simulation:\n  dt: 0.0005\n", "test.yaml").simulation_settings();
  EXPECT_EQ(half.controller_period_steps, 2);
  EXPECT_EQ(half.controller_period(), 1e-3);
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  log_every: 0\n"),
              HasSubstr("field 'simulation.log_every': expected an integer in [1, "));
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  duration: 1e6\n"),
              HasSubstr("field 'simulation.duration': at most 86400 s (one simulated day)"));
  // What the flight loop would refuse without naming the file or the field.
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  duration: 1e-4\n"),
              HasSubstr("field 'simulation.duration': the flight (0.0001 s) is shorter than one controller period"));
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  controller_period_steps: 100000\n"),
              HasSubstr("field 'simulation.controller_period_steps': the flight (12 s) is shorter than one controller"));
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  dt: 1e-13\n"),
              HasSubstr("field 'simulation.dt': 1e-13 s: more than 2^31 - 1 plant steps per controller period"));
}

TEST(Scenario, AtTwiceTheSpeedTheFlightCoversTheSamePathInHalfTheTime) {
  const Scenario scenario = parse_scenario(kHeader + kTakeoff + kHover + "simulation:\n  duration: 10\n", "test.yaml");
  const Scenario faster = scenario.at_speed(2.0);
  EXPECT_EQ(faster.duration, 6.0);
  EXPECT_EQ(faster.trajectory.end_time(), 6.0);
  EXPECT_EQ(faster.simulation_settings().duration, 5.0);
  EXPECT_EQ(faster.trajectory.position(1.75), scenario.trajectory.position(3.5));
  // The physics keeps its clock.
  EXPECT_EQ(faster.simulation_settings().dt, scenario.simulation_settings().dt);
  EXPECT_EQ(faster.simulation_settings().wind_gust.onset, scenario.simulation_settings().wind_gust.onset);
  const Scenario slower = parse_scenario(kHeader + kTakeoff + kHover, "test.yaml").at_speed(0.5);
  EXPECT_EQ(slower.simulation_settings().duration, 24.0);
  EXPECT_THROW(scenario.at_speed(0.0), Error);
}

TEST(Scenario, InitialPositionStartsTheCommand) {
  const Scenario scenario =
      parse_scenario("duration: 5\ninitial_state:\n  position: [1, 2, 3.5]\nphases:\n"
                     "  - {type: hold, time: [0, 5]}\n",
                     "test.yaml");
  EXPECT_EQ(scenario.initial_state.segment<3>(heli::kXp), Eigen::Vector3d(1.0, 2.0, -3.5));
  EXPECT_EQ(scenario.trajectory.position(2.0), Eigen::Vector3d(1.0, 2.0, -3.5));
  EXPECT_EQ(scenario.name, "test");  // defaults to the file's stem
}

TEST(Scenario, UnknownKeysNameTheirLineAndTheAllowedFields) {
  EXPECT_THAT(error_of("name: test\nduraton: 12\n"),
              HasSubstr("test.yaml:2:1: field 'duraton': unknown field (allowed: name, description, duration"));
  EXPECT_THAT(error_of(kHeader + kTakeoff + "  - name: hover\n    type: hold\n    time: [7, 12]\n    to: [0, 0, 1]\n"),
              HasSubstr("test.yaml:11:5: field 'phases.hover.to': unknown field (allowed: name, type, time)"));
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  model:\n    rotor_speed: governor\n"),
              HasSubstr("test.yaml:13:5: field 'simulation.model.rotor_speed': unknown field"));
}

TEST(Scenario, WrongTypesAndValuesNameTheirLineAndField) {
  EXPECT_THAT(error_of("name: test\nduration: long\n"), HasSubstr("test.yaml:2:11: field 'duration': expected a number"));
  EXPECT_THAT(error_of("name: test\nduration: -5\n"), HasSubstr("test.yaml:2:11: field 'duration': must be > 0"));
  EXPECT_THAT(error_of(kHeader + "  - name: takeoff\n    type: ramp\n    time: [0, 7]\n    to: [0, 0]\n" + kHover),
              HasSubstr("test.yaml:7:9: field 'phases.takeoff.to': expected 3 entries, got 2"));
  EXPECT_THAT(error_of(kHeader + "  - name: takeoff\n    type: ramp\n    time: [0, 7]\n    to: [0, 0, -1]\n" + kHover),
              HasSubstr("test.yaml:7:9: field 'phases.takeoff.to': altitude h (the third entry) must be >= 0"));
  EXPECT_THAT(error_of("duration: 50\nphases:\n  - name: figure8\n    type: figure8\n    time: [0, 50]\n"
                       "    amplitude_x: 8\n    amplitude_y: 4\n    period: 0\n"),
              HasSubstr("test.yaml:8:13: field 'phases.figure8.period': must be > 0"));
  EXPECT_THAT(error_of("duration: 50\nphases:\n  - name: figure8\n    type: figure8\n    time: [0, 50]\n"
                       "    amplitude_x: 8\n    amplitude_y: 4\n"),
              HasSubstr("test.yaml:3:5: field 'phases.figure8.period': missing (required)"));
  EXPECT_THAT(error_of(kHeader + "  - name: takeoff\n    type: spiral\n    time: [0, 7]\n" + kHover),
              HasSubstr("test.yaml:5:11: field 'phases[0].type': expected one of hold, ramp, step"));
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  model:\n    rotor_speed_model: turbo\n"),
              HasSubstr("test.yaml:13:24: field 'simulation.model.rotor_speed_model': model option 'rotor_speed_model': "
                        "unknown value 'turbo'"));
  EXPECT_THAT(error_of(kHeader + kTakeoff + kHover + "simulation:\n  disturbances:\n    wind_gust: maybe\n"),
              HasSubstr("test.yaml:13:16: field 'simulation.disturbances.wind_gust': expected true or false"));
  EXPECT_THAT(error_of("- just\n- a list\n"), HasSubstr("test.yaml:1:1: field 'scenario': expected a map of fields"));
}

TEST(Scenario, PhasesMustBeInOrderBackToBackAndCoverTheDuration) {
  // Overlap: hover starts at 6 s while takeoff runs to 7 s.
  EXPECT_THAT(error_of(kHeader + kTakeoff + "  - name: hover\n    type: hold\n    time: [6, 12]\n"),
              HasSubstr("test.yaml:10:11: field 'phases.hover.time': starts at 6 s, before phase 'takeoff' ends at 7 s"));
  // Unsorted: the hover is listed first.
  EXPECT_THAT(error_of(kHeader + "  - name: hover\n    type: hold\n    time: [7, 12]\n" +
                       "  - name: takeoff\n    type: ramp\n    time: [0, 7]\n    to: [0, 0, 3.5]\n"),
              HasSubstr("test.yaml:6:11: field 'phases.hover.time': the first phase must start at 0 s, not 7 s"));
  EXPECT_THAT(error_of(kHeader + kTakeoff + "  - name: hover\n    type: hold\n    time: [8, 12]\n"),
              HasSubstr("test.yaml:10:11: field 'phases.hover.time': starts at 8 s, leaving a gap after phase 'takeoff'"));
  EXPECT_THAT(error_of(kHeader + kTakeoff + "  - name: hover\n    type: hold\n    time: [7, 7]\n"),
              HasSubstr("test.yaml:10:11: field 'phases.hover.time': ends at 7 s, not after its start 7 s"));
  EXPECT_THAT(error_of(kHeader + kTakeoff + "  - name: hover\n    type: hold\n    time: [7, -12]\n"),
              HasSubstr("test.yaml:10:15: field 'phases.hover.time[1]': expected a number in [0, inf]"));
  EXPECT_THAT(error_of("name: test\nduration: 20\nphases:\n" + kTakeoff + kHover),
              HasSubstr("test.yaml:2:11: field 'duration': 20 s, but the phases end at 12 s"));
  EXPECT_THAT(error_of("name: test\nduration: 20\nphases: []\n"),
              HasSubstr("test.yaml:3:9: field 'phases': expected a non-empty list of phases"));
}

TEST(Scenario, MissingFileAndBadYamlAreOneClearLine) {
  try {
    load_scenario("/nonexistent/scenario.yaml");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()),
              "cannot read /nonexistent/scenario.yaml: No such file or directory");
  }
  EXPECT_THAT(error_of("name: test\nduration: [12\n"), HasSubstr("test.yaml:3:1: invalid YAML: "));
}

}  // namespace
}  // namespace thetad
