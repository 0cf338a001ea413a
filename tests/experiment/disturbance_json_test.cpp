#include "settings/disturbance_json.hpp"

#include <gtest/gtest.h>

namespace thetad {
namespace {

using Json = nlohmann::ordered_json;

TEST(DisturbanceJson, EverySettingComesBackAsWritten) {
  sim::SimulationSettings settings;
  settings.turbulence.model = sim::TurbulenceSettings::Model::gauss_markov;
  settings.turbulence.intensity = sim::TurbulenceIntensity::moderate;
  settings.turbulence.scale = 0.1 + 0.2;  // not a short decimal: the round trip must be exact
  settings.turbulence.sigma = {1.0 / 3.0, 0.5, 0.0};
  settings.turbulence.correlation_time = 2.5;
  settings.discrete_gusts = {{2, -1.5, 3.0, 0.7}};
  settings.sensor_noise.density[4] = 1e-3 / 7.0;
  settings.sensor_noise.bias[13] = 0.01;
  settings.servos.time_constant[1] = 0.03;
  settings.servos.delay_samples = 4;
  settings.computer.latency = sim::FlightComputerSettings::Latency::step_time;
  settings.computer.slowdown = 1.0 / 3.0;
  settings.computer.overrun = sim::FlightComputerSettings::Overrun::abort;
  settings.computer.step_times = {{"theta-d", 2.1e-6 / 3.0}, {"sdre", 4.7e-5}};
  settings.computer.step_time = 4.7e-5;
  settings.computer.step_time_source = "bench.json (sha256 ab, p99)";
  Json json;
  write_beyond_paper(settings, json);
  sim::SimulationSettings read;
  read_beyond_paper(Json::parse(json.dump())).apply(read);
  EXPECT_EQ(read.turbulence.model, settings.turbulence.model);
  EXPECT_EQ(read.turbulence.intensity, settings.turbulence.intensity);
  EXPECT_EQ(read.turbulence.scale, settings.turbulence.scale);
  EXPECT_EQ(read.turbulence.sigma, settings.turbulence.sigma);
  EXPECT_EQ(read.turbulence.correlation_time, 2.5);
  ASSERT_EQ(read.discrete_gusts.size(), 1u);
  EXPECT_EQ(read.discrete_gusts[0].axis, 2);
  EXPECT_EQ(read.discrete_gusts[0].duration, 0.7);
  EXPECT_EQ(read.sensor_noise.density, settings.sensor_noise.density);
  EXPECT_EQ(read.sensor_noise.bias, settings.sensor_noise.bias);
  EXPECT_EQ(read.servos.time_constant, settings.servos.time_constant);
  EXPECT_EQ(read.servos.delay_samples, 4);
  EXPECT_EQ(read.computer.latency, settings.computer.latency);
  EXPECT_EQ(read.computer.slowdown, settings.computer.slowdown);
  EXPECT_EQ(read.computer.overrun, settings.computer.overrun);
  EXPECT_EQ(read.computer.step_times, settings.computer.step_times);
  EXPECT_EQ(read.computer.step_time, 4.7e-5);
  EXPECT_EQ(read.computer.step_time_source, settings.computer.step_time_source);
}

// A result written before these settings existed flew without them: its replay must too, even
// where the scenario (or a control) would now turn them on.
TEST(DisturbanceJson, AnOlderResultReadsAsEverythingOff) {
  sim::SimulationSettings settings;
  settings.turbulence.model = sim::TurbulenceSettings::Model::dryden;
  settings.servos.delay_samples = 2;
  settings.sensor_noise.density.setConstant(1.0);
  settings.discrete_gusts = {{0, 1.0, 0.0, 1.0}};
  settings.computer.latency = sim::FlightComputerSettings::Latency::fixed;
  read_beyond_paper(Json{{"dt_s", 0.001}}).apply(settings);
  EXPECT_FALSE(settings.computer.active());
  EXPECT_FALSE(settings.turbulence.active());
  EXPECT_FALSE(settings.servos.active());
  EXPECT_FALSE(settings.sensor_noise.active());
  EXPECT_TRUE(settings.discrete_gusts.empty());
}

}  // namespace
}  // namespace thetad
