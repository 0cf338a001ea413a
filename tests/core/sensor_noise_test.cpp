#include "core/sim/sensor_noise.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tests/welch_psd.hpp"

namespace thetad::sim {
namespace {

using thetad::testing::welch_psd;

// One channel's noise (the whole vector's entry `channel`) over `seconds` sampled at `rate`.
std::vector<double> record(const SensorNoiseSettings& settings, int channel, double rate, double seconds,
                           std::uint64_t seed) {
  SensorNoise noise(settings, 1.0 / rate);
  noise.start(seed);
  std::vector<double> values(static_cast<std::size_t>(seconds * rate));
  for (double& value : values) {
    SensedVector sensed = SensedVector::Zero();
    noise.add(sensed);
    value = sensed[channel];
  }
  return values;
}

// The density's PSD over 0.1-2 Hz at controller rates of 1 kHz and 250 Hz, and the in-band power
// the same at both: what makes the noise a property of the sensor, not of the loop's rate.
TEST(SensorNoise, DensityIsThePsdAtEveryControllerRate) {
  SensorNoiseSettings settings;
  settings.density[0] = 0.01;   // x_p, m/√Hz
  settings.density[10] = 2e-3;  // q, rad/s/√Hz
  for (int channel : {0, 10}) {
    const double density2 = settings.density[channel] * settings.density[channel];
    std::vector<double> band_power;
    for (double rate : {1000.0, 250.0}) {
      // 32 s segments (bins 1/32 Hz apart) over 600 s: 36 segments, 61 bins in the band.
      const auto spectrum = welch_psd(record(settings, channel, rate, 600.0, 8), rate,
                                      static_cast<std::size_t>(32.768 * rate));
      const auto [estimated, specified] = spectrum.band_means(0.1, 2.0, [&](double) { return density2; });
      EXPECT_NEAR(estimated / specified, 1.0, 0.10) << "channel " << channel << " at " << rate << " Hz";
      band_power.push_back(estimated * 1.9);
    }
    EXPECT_NEAR(band_power[1] / band_power[0], 1.0, 0.10) << "channel " << channel;
  }
}

TEST(SensorNoise, SampleSigmaIsTheDensityTimesTheRootOfHalfTheRate) {
  SensorNoiseSettings settings;
  settings.density.setConstant(0.02);
  EXPECT_NEAR(SensorNoise(settings, 1e-3).sample_sigma()[3], 0.02 * std::sqrt(500.0), 1e-12);
  EXPECT_NEAR(SensorNoise(settings, 4e-3).sample_sigma()[3], 0.02 * std::sqrt(125.0), 1e-12);
}

TEST(SensorNoise, BiasIsDrawnOncePerRunWithItsSigma) {
  SensorNoiseSettings settings;
  settings.bias[6] = 0.01;  // φ, rad
  const auto run = record(settings, 6, 100.0, 1.0, 3);
  for (double value : run) EXPECT_EQ(value, run.front());
  double squares = 0.0;
  const int runs = 4000;
  for (int seed = 0; seed < runs; ++seed) {
    SensorNoise noise(settings, 1e-3);
    noise.start(static_cast<std::uint64_t>(seed));
    squares += noise.biases()[6] * noise.biases()[6];
  }
  // The sample σ of 4000 normals: relative standard error 1.1 %.
  EXPECT_NEAR(std::sqrt(squares / runs), 0.01, 0.01 * 4.0 / std::sqrt(2.0 * runs));
}

TEST(SensorNoise, OffLeavesTheMeasurementAndRefusesNegativeValues) {
  SensorNoiseSettings settings;
  EXPECT_FALSE(settings.active());
  SensorNoise noise(settings, 1e-3);
  noise.start(1);
  SensedVector sensed = SensedVector::LinSpaced(-1.0, 1.0);
  const SensedVector before = sensed;
  noise.add(sensed);
  EXPECT_EQ(sensed, before);
  settings.density[2] = -1.0;
  EXPECT_THROW(SensorNoise(settings, 1e-3), Error);
}

}  // namespace
}  // namespace thetad::sim
