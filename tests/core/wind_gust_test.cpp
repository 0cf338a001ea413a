#include "core/sim/wind_gust.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/sim/noise.hpp"

namespace thetad::sim {
namespace {

struct Moments {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();
  double north_lag1_correlation = 0.0;
};

// Samples the gust `count` times at altitude 3.5 m and returns its sample moments.
Moments sample_moments(const WindGustSettings& settings, double period, int count, std::uint64_t seed) {
  WindGust gust(settings, period);
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Vector3d> samples(static_cast<std::size_t>(count));
  for (auto& sample : samples) sample = gust.sample(0.0, -3.5, standard_normal_pair(rng));
  Moments m;
  for (const auto& s : samples) m.mean += s;
  m.mean /= count;
  double lag_product = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    m.sigma += (samples[i] - m.mean).cwiseAbs2();
    if (i > 0) lag_product += (samples[i].x() - m.mean.x()) * (samples[i - 1].x() - m.mean.x());
  }
  m.north_lag1_correlation = lag_product / m.sigma.x();
  m.sigma = (m.sigma / (count - 1)).cwiseSqrt();
  return m;
}

TEST(MeanNorthWind, FollowsSpecFormulaWithAltitudeAndMeanFloors) {
  EXPECT_NEAR(mean_north_wind(-3.5), 1.258 + 0.949 * std::log10(3.5), 1e-15);
  EXPECT_NEAR(mean_north_wind(-3.5), 1.774, 5e-4);  // docs/model.md §9.2
  EXPECT_NEAR(mean_north_wind(0.0), 0.309, 5e-4);   // h floored at 0.1 m
  EXPECT_EQ(mean_north_wind(0.5), mean_north_wind(0.0));  // below ground: same floor
  EXPECT_GE(mean_north_wind(-0.05), 0.0);
}

TEST(WindGust, DisabledGivesNoWind) {
  WindGustSettings settings;
  settings.enabled = false;
  WindGust gust(settings, 1e-3);
  EXPECT_EQ(gust.sample(0.0, -3.5, Eigen::Vector2d(1.0, -2.0)), Eigen::Vector3d::Zero());
}

TEST(WindGust, AmplitudeScaleMultipliesTheWholeWindFromTheOnset) {
  WindGustSettings settings;
  settings.amplitude_scale = 2.5;
  settings.onset = 1.0;
  WindGust scaled(settings, 1e-3);
  WindGust paper(WindGustSettings{}, 1e-3);
  const Eigen::Vector2d normal(0.3, -1.2);
  EXPECT_EQ(scaled.sample(0.999, -3.5, normal), Eigen::Vector3d::Zero());  // calm before the onset
  const Eigen::Vector3d expected = 2.5 * paper.sample(1.0, -3.5, normal);
  EXPECT_EQ(scaled.sample(1.0, -3.5, normal), expected);
  EXPECT_GT(expected.x(), 2.5 * mean_north_wind(-3.5) - 2.5 * 0.199 * 0.3 - 1e-12);
  settings.amplitude_scale = -1.0;
  EXPECT_THROW(WindGust(settings, 1e-3), Error);
  settings.amplitude_scale = 1.0;
  settings.onset = -0.1;
  EXPECT_THROW(WindGust(settings, 1e-3), Error);
}

// 200 000 independent samples: the standard error of the mean is sigma/sqrt(N) = 4.4e-4 m/s and
// that of the sample sigma about sigma/sqrt(2N) = 3.1e-4 m/s. Bounds of 4 standard errors fail by
// chance with probability ~6e-5 each (and the seed is fixed, so the test is deterministic).
TEST(WindGust, HeldWhiteHasSpecMeanAndSigmaAt3p5m) {
  constexpr int kCount = 200000;
  const WindGustSettings settings;
  const Moments m = sample_moments(settings, 1e-3, kCount, 7);
  const double mean_error = 4.0 * settings.sigma / std::sqrt(kCount);
  const double sigma_error = 4.0 * settings.sigma / std::sqrt(2.0 * kCount);
  EXPECT_NEAR(m.mean.x(), mean_north_wind(-3.5), mean_error);
  EXPECT_NEAR(m.mean.y(), 0.0, mean_error);
  EXPECT_EQ(m.mean.z(), 0.0);
  EXPECT_NEAR(m.sigma.x(), settings.sigma, sigma_error);
  EXPECT_NEAR(m.sigma.y(), settings.sigma, sigma_error);
  EXPECT_EQ(m.sigma.z(), 0.0);
  EXPECT_NEAR(m.north_lag1_correlation, 0.0, 4.0 / std::sqrt(kCount));  // independent samples
}

// AR(1) with a = exp(-T_c/tau) = exp(-0.05): the effective sample count for the mean is
// N (1 - a)/(1 + a) = N/40 = 10 000, so the mean's standard error is sigma/100 = 2e-3 m/s; the
// sample variance's relative standard error is sqrt(2 (1 + a^2)/((1 - a^2) N)) = 1 %, i.e. 0.5 %
// on sigma. Bounds: 4 standard errors.
TEST(WindGust, GaussMarkovKeepsStationarySigmaWithOneSecondCorrelation) {
  constexpr int kCount = 400000;
  constexpr double kPeriod = 0.05;
  WindGustSettings settings;
  settings.model = WindGustSettings::Model::gauss_markov;
  const Moments m = sample_moments(settings, kPeriod, kCount, 11);
  const double a = std::exp(-kPeriod / settings.correlation_time);
  EXPECT_NEAR(m.mean.x(), mean_north_wind(-3.5), 4.0 * settings.sigma / 100.0);
  EXPECT_NEAR(m.mean.y(), 0.0, 4.0 * settings.sigma / 100.0);
  EXPECT_NEAR(m.sigma.x(), settings.sigma, 0.02 * settings.sigma);
  EXPECT_NEAR(m.sigma.y(), settings.sigma, 0.02 * settings.sigma);
  EXPECT_NEAR(m.north_lag1_correlation, a, 0.01);
}

TEST(WindGust, RejectsNonPositiveCorrelationTime) {
  WindGustSettings settings;
  settings.model = WindGustSettings::Model::gauss_markov;
  settings.correlation_time = 0.0;
  EXPECT_THROW(WindGust(settings, 1e-3), Error);
}

}  // namespace
}  // namespace thetad::sim
