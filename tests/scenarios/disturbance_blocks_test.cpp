#include "settings/disturbance_blocks.hpp"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/helicopter/uncertainty.hpp"
#include "scenarios/scenario.hpp"
#include "tests/error_message.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;
using thetad::testing::error_message;

const std::string kHoldFile = "name: test\nduration: 5\nphases:\n  - {name: hold, type: hold, time: [0, 5]}\nsimulation:\n";

sim::SimulationSettings settings_of(const std::string& simulation) {
  return parse_scenario(kHoldFile + simulation, "test.yaml").simulation_settings();
}

std::string simulation_error_of(const std::string& simulation) {
  return error_message([&] { parse_scenario(kHoldFile + simulation, "test.yaml"); });
}

TEST(DisturbanceBlocks, AbsentBlocksLeaveEverythingOff) {
  const sim::SimulationSettings settings = settings_of("  seed: 4\n");
  EXPECT_FALSE(settings.turbulence.active());
  EXPECT_TRUE(settings.discrete_gusts.empty());
  EXPECT_FALSE(settings.sensor_noise.active());
  EXPECT_FALSE(settings.servos.active());
}

TEST(DisturbanceBlocks, WindSensorNoiseAndServosReachTheSettings) {
  const sim::SimulationSettings settings = settings_of(
      "  wind:\n    model: dryden\n    intensity: severe\n    scale: 0.5\n    airspeed_floor: 2\n"
      "    gusts:\n      - {axis: east, amplitude: -2, start: 1, duration: 0.5}\n"
      "  sensor_noise:\n    density: {position: 0.01, rates: [1e-3, 2e-3, 3e-3]}\n    bias: {attitude: 0.002}\n"
      "  servos: {time_constant: [0.02, 0.03, 0.02, 0.04, 0.04], delay_samples: 3}\n");
  EXPECT_EQ(settings.turbulence.model, sim::TurbulenceSettings::Model::dryden);
  EXPECT_EQ(settings.turbulence.intensity, sim::TurbulenceIntensity::severe);
  EXPECT_EQ(settings.turbulence.scale, 0.5);
  EXPECT_EQ(settings.turbulence.airspeed_floor, 2.0);
  ASSERT_EQ(settings.discrete_gusts.size(), 1u);
  EXPECT_EQ(settings.discrete_gusts[0].axis, 1);
  EXPECT_EQ(settings.discrete_gusts[0].amplitude, -2.0);
  EXPECT_EQ(settings.sensor_noise.density.head<3>(), Eigen::Vector3d::Constant(0.01));
  EXPECT_EQ(settings.sensor_noise.density.segment<3>(9), Eigen::Vector3d(1e-3, 2e-3, 3e-3));
  EXPECT_EQ(settings.sensor_noise.density[5], 0.0);
  EXPECT_EQ(settings.sensor_noise.bias.segment<3>(6), Eigen::Vector3d::Constant(0.002));
  EXPECT_EQ(settings.servos.time_constant[3], 0.04);
  EXPECT_EQ(settings.servos.delay_samples, 3);
}

TEST(DisturbanceBlocks, SigmaAtABandwidthIsADensity) {
  const sim::SimulationSettings settings =
      settings_of("  sensor_noise: {sigma: {velocity: 0.2}, bandwidth: 100}\n");
  EXPECT_NEAR(settings.sensor_noise.density[3], 0.02, 1e-15);  // σ / √B
}

TEST(DisturbanceBlocks, GaussMarkovTakesItsSigmaPerAxis) {
  const sim::SimulationSettings settings =
      settings_of("  wind: {model: gauss_markov, sigma: [1, 0.5, 0.1], correlation_time: 3}\n");
  EXPECT_EQ(settings.turbulence.sigma, Eigen::Vector3d(1.0, 0.5, 0.1));
  EXPECT_EQ(settings.turbulence.correlation_time, 3.0);
}

TEST(DisturbanceBlocks, BadValuesNameTheFileTheFieldAndTheReason) {
  EXPECT_THAT(simulation_error_of("  wind: {model: karman}\n"),
              HasSubstr("test.yaml:6:17: field 'simulation.wind.model': expected one of paper, dryden, gauss_markov"));
  EXPECT_THAT(simulation_error_of("  wind: {model: gauss_markov}\n"), HasSubstr("field 'simulation.wind.sigma': missing"));
  EXPECT_THAT(simulation_error_of("  wind: {intensity: extreme}\n"), HasSubstr("field 'simulation.wind.intensity'"));
  EXPECT_THAT(simulation_error_of("  wind: {gusts: [{axis: up, amplitude: 1, start: 0, duration: 1}]}\n"),
              HasSubstr("field 'simulation.wind.gusts[0].axis': expected one of north, east, down"));
  EXPECT_THAT(simulation_error_of("  wind: {gusts: [{axis: east, amplitude: 1, start: 0}]}\n"),
              HasSubstr("field 'simulation.wind.gusts[0].duration': missing (required)"));
  EXPECT_THAT(simulation_error_of("  sensor_noise: {sigma: {position: 0.1}}\n"),
              HasSubstr("field 'simulation.sensor_noise.bandwidth': missing"));
  EXPECT_THAT(simulation_error_of("  sensor_noise: {density: {position: -1}}\n"),
              HasSubstr("field 'simulation.sensor_noise.density.position'"));
  EXPECT_THAT(simulation_error_of("  sensor_noise: {density: {altitude: 1}}\n"),
              HasSubstr("field 'simulation.sensor_noise.density.altitude': unknown field"));
  EXPECT_THAT(simulation_error_of("  servos: {time_constant: [0.1, 0.1]}\n"),
              HasSubstr("field 'simulation.servos.time_constant': expected 5 entries, got 2"));
  EXPECT_THAT(simulation_error_of("  servos: {delay_samples: 1.5}\n"), HasSubstr("field 'simulation.servos.delay_samples'"));
}

// Table 1's parameter deviations by name (a worst case to fly again): the others 0, each in [-1, 1].
TEST(DisturbanceBlocks, ParameterDeviationsByNameReplaceTheDraw) {
  EXPECT_TRUE(settings_of("  seed: 4\n").parameter_deviations.empty());
  const sim::SimulationSettings settings =
      settings_of("  disturbances:\n    parameter_deviations: {m: -1, I_xx: 0.25}\n");
  ASSERT_EQ(settings.parameter_deviations.size(), 21u);
  const auto names = heli::parameter_uncertainty_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    const double expected = names[i] == "m" ? -1.0 : names[i] == "I_xx" ? 0.25 : 0.0;
    EXPECT_EQ(settings.parameter_deviations[i], expected) << names[i];
  }
  EXPECT_THAT(simulation_error_of("  disturbances:\n    parameter_deviations: {mass: 0.5}\n"),
              HasSubstr("field 'simulation.disturbances.parameter_deviations.mass': not a parameter of Table 1"));
  EXPECT_THAT(simulation_error_of("  disturbances:\n    parameter_deviations: {m: 1.5}\n"),
              HasSubstr("simulation.disturbances.parameter_deviations.m"));
}

}  // namespace
}  // namespace thetad
