#include "core/sim/turbulence.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "core/sim/discrete_gust.hpp"
#include "core/sim/gauss_markov.hpp"
#include "core/sim/noise.hpp"
#include "core/sim/wind_gust.hpp"
#include "tests/welch_psd.hpp"

namespace thetad::sim {
namespace {

using namespace heli;
using thetad::testing::welch_psd;

constexpr double kFoot = 0.3048;
constexpr double kKnot = 1852.0 / 3600.0;
// Welch segments of 64 s (resolution 1/64 Hz: 0.1 Hz is the seventh bin, far from the leakage of
// the spectra's low-frequency peak through the Hann window) over records of 4800 s (145 segments):
// the band mean's relative standard error is then about 2.5 % (measured over seeds).
constexpr double kSegmentSeconds = 65.536, kRecordSeconds = 4800.0;
constexpr double kBandLow = 0.1, kBandHigh = 2.0, kTolerance = 0.10;

// Level flight north at `airspeed` (m/s, body u) at `altitude` (m), heading north: the Dryden u,
// v, w are then north, east and down.
Eigen::VectorXd level_flight(double altitude, double airspeed) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kStateDim);
  x[kZp] = -altitude;
  x[kU] = airspeed;
  x[kS] = 1.0;
  return x;
}

// The turbulence of `settings` at state x, stepped at `rate` (Hz) for `seconds`: one record per
// NED axis.
std::vector<std::vector<double>> record(const TurbulenceSettings& settings, const Eigen::VectorXd& x, double rate,
                                        double seconds, std::uint64_t seed) {
  Turbulence turbulence(settings);
  turbulence.start(seed);
  const auto samples = static_cast<std::size_t>(seconds * rate);
  std::vector<std::vector<double>> axes(3, std::vector<double>(samples));
  for (std::size_t k = 0; k < samples; ++k) {
    const Eigen::Vector3d wind = turbulence.wind(x);
    for (int a = 0; a < 3; ++a) axes[static_cast<std::size_t>(a)][k] = wind[a];
    turbulence.step(1.0 / rate, x, Eigen::Vector3d::Zero());
  }
  return axes;
}

std::size_t segment_length(double rate) { return static_cast<std::size_t>(std::lround(kSegmentSeconds * rate)); }

TEST(DrydenScales, FollowTheLowAltitudeFormulasInFeetAndKnots) {
  const double h = 100.0;  // ft
  const DrydenScales scales = dryden_scales(h * kFoot, TurbulenceIntensity::moderate);
  const double base = 0.177 + 0.000823 * h;
  EXPECT_NEAR(scales.length[2], h * kFoot, 1e-12);
  EXPECT_NEAR(scales.length[0], h / std::pow(base, 1.2) * kFoot, 1e-9);
  EXPECT_EQ(scales.length[1], scales.length[0]);
  EXPECT_NEAR(scales.sigma[2], 0.1 * 30.0 * kKnot, 1e-12);
  EXPECT_NEAR(scales.sigma[0], 0.1 * 30.0 * kKnot / std::pow(base, 0.4), 1e-12);
  EXPECT_EQ(scales.sigma[1], scales.sigma[0]);
  EXPECT_NEAR(wind_speed_at_20ft(TurbulenceIntensity::light), 15.0 * kKnot, 1e-12);
  EXPECT_NEAR(wind_speed_at_20ft(TurbulenceIntensity::severe), 45.0 * kKnot, 1e-12);
}

TEST(DrydenScales, ClampTheAltitudeTo10To1000Feet) {
  const auto at = [](double h) { return dryden_scales(h, TurbulenceIntensity::light); };
  for (double below : {-2.0, 0.0, 1.0}) {
    EXPECT_EQ(at(below).length, at(kDrydenMinAltitude).length) << below;
    EXPECT_EQ(at(below).sigma, at(kDrydenMinAltitude).sigma) << below;
  }
  EXPECT_EQ(at(2000.0).length, at(kDrydenMaxAltitude).length);
  EXPECT_NEAR(kDrydenMinAltitude, 10.0 * kFoot, 1e-12);
}

// The Welch PSD of each Dryden component over 0.1-2 Hz against the specification, with the
// filters stepped at 1 kHz and at 250 Hz: the same spectrum at both rates.
TEST(Dryden, SpectraMatchTheSpecificationAtEveryStepRate) {
  TurbulenceSettings settings;
  settings.model = TurbulenceSettings::Model::dryden;
  settings.intensity = TurbulenceIntensity::moderate;
  const double altitude = 10.0, airspeed = 5.0;
  const DrydenScales scales = dryden_scales(altitude, settings.intensity);
  for (double rate : {1000.0, 250.0}) {
    const auto axes = record(settings, level_flight(altitude, airspeed), rate, kRecordSeconds, 11);
    for (int a = 0; a < 3; ++a) {
      const auto spectrum = welch_psd(axes[static_cast<std::size_t>(a)], rate, segment_length(rate));
      const auto [estimated, specified] =
          spectrum.band_means(kBandLow, kBandHigh, [&](double f) { return dryden_psd(a, scales, airspeed, f); });
      EXPECT_NEAR(estimated / specified, 1.0, kTolerance) << "axis " << a << " at " << rate << " Hz";
    }
  }
}

// The sample variance of each component against σ², within three of its standard errors: for a
// stationary Gaussian record of length T, Var(s²) ≈ (1/T) ∫_0^∞ G(f)² df.
TEST(Dryden, VarianceIsSigmaSquaredWithinItsSamplingError) {
  TurbulenceSettings settings;
  settings.model = TurbulenceSettings::Model::dryden;
  settings.intensity = TurbulenceIntensity::severe;
  settings.scale = 0.5;
  const double altitude = 10.0, airspeed = 40.0, rate = 250.0, seconds = 3000.0;
  const DrydenScales scales = dryden_scales(altitude, settings.intensity);
  const auto axes = record(settings, level_flight(altitude, airspeed), rate, seconds, 5);
  for (int a = 0; a < 3; ++a) {
    const auto& x = axes[static_cast<std::size_t>(a)];
    double sum = 0.0, squares = 0.0;
    for (double v : x) sum += v, squares += v * v;
    const double n = static_cast<double>(x.size()), mean = sum / n, variance = squares / n - mean * mean;
    const double sigma2 = std::pow(settings.scale * scales.sigma[a], 2);
    double integral = 0.0;  // ∫ G² df by the midpoint rule to 200 Hz, far in the tail
    for (double f = 0.0005; f < 200.0; f += 0.001) {
      const double g = settings.scale * settings.scale * dryden_psd(a, scales, airspeed, f);
      integral += g * g * 0.001;
    }
    const double standard_error = std::sqrt(integral / seconds);
    EXPECT_NEAR(variance, sigma2, 3.0 * standard_error) << "axis " << a << ": sigma^2 " << sigma2;
    EXPECT_LT(standard_error / sigma2, 0.1) << "the record is too short to say anything";
  }
}

TEST(Dryden, HoverTakesTheAirspeedFloorAndTheHeadingTurnsTheComponents) {
  TurbulenceSettings settings;
  settings.model = TurbulenceSettings::Model::dryden;
  Eigen::VectorXd hover = level_flight(3.5, 0.0), at_floor = level_flight(3.5, settings.airspeed_floor);
  Turbulence a(settings), b(settings);
  a.start(3);
  b.start(3);
  for (int k = 0; k < 100; ++k) {
    a.step(1e-3, hover, Eigen::Vector3d::Zero());
    b.step(1e-3, at_floor, Eigen::Vector3d::Zero());
  }
  EXPECT_EQ(a.wind(hover), b.wind(at_floor));
  Eigen::VectorXd east = hover;
  east[kPsi] = std::numbers::pi / 2.0;
  const Eigen::Vector3d north_frame = a.wind(hover), turned = a.wind(east);
  EXPECT_NEAR(turned.x(), -north_frame.y(), 1e-12);  // v (to the right of east: south)
  EXPECT_NEAR(turned.y(), north_frame.x(), 1e-12);   // u along the heading: east
  EXPECT_EQ(turned.z(), north_frame.z());
}

TEST(GaussMarkov, SpectraMatchTheSpecificationAtEveryStepRate) {
  TurbulenceSettings settings;
  settings.model = TurbulenceSettings::Model::gauss_markov;
  settings.sigma = {1.0, 0.5, 0.2};
  settings.correlation_time = 2.0;
  for (double rate : {1000.0, 250.0}) {
    const auto axes = record(settings, level_flight(3.5, 0.0), rate, kRecordSeconds, 2);
    for (int a = 0; a < 3; ++a) {
      const auto spectrum = welch_psd(axes[static_cast<std::size_t>(a)], rate, segment_length(rate));
      const auto [estimated, specified] = spectrum.band_means(
          kBandLow, kBandHigh, [&](double f) { return gauss_markov_psd(settings.sigma[a], 2.0, f); });
      EXPECT_NEAR(estimated / specified, 1.0, kTolerance) << "axis " << a << " at " << rate << " Hz";
    }
  }
}

// The paper's gust as it always was: white, held over each controller sample, so its density
// below 2 Hz is 2 σ² T_c and changes with the controller rate (docs/model.md §9.2, §15).
TEST(PaperGust, IsWhiteAtItsControllerRate) {
  WindGustSettings settings;
  for (double rate : {1000.0, 250.0}) {
    WindGust gust(settings, 1.0 / rate);
    std::mt19937_64 rng(4);
    std::vector<double> east(static_cast<std::size_t>(600.0 * rate));
    for (double& value : east) value = gust.sample(0.0, -3.5, standard_normal_pair(rng)).y();
    const auto spectrum = welch_psd(east, rate, segment_length(rate));
    const auto [estimated, specified] =
        spectrum.band_means(kBandLow, kBandHigh, [&](double) { return 2.0 * settings.sigma * settings.sigma / rate; });
    EXPECT_NEAR(estimated / specified, 1.0, kTolerance) << rate << " Hz";
  }
}

TEST(Turbulence, ScaleMultipliesTheSameRealization) {
  TurbulenceSettings settings;
  settings.model = TurbulenceSettings::Model::dryden;
  TurbulenceSettings doubled = settings;
  doubled.scale = 2.0;
  const Eigen::VectorXd x = level_flight(20.0, 8.0);
  const auto once = record(settings, x, 250.0, 2.0, 9), twice = record(doubled, x, 250.0, 2.0, 9);
  for (std::size_t k = 0; k < once[0].size(); ++k) EXPECT_EQ(twice[1][k], 2.0 * once[1][k]);
}

TEST(Turbulence, RefusesSettingsOutOfRange) {
  TurbulenceSettings settings;
  settings.airspeed_floor = 0.0;
  EXPECT_THROW(Turbulence{settings}, Error);
  settings = {};
  settings.correlation_time = -1.0;
  EXPECT_THROW(Turbulence{settings}, Error);
  settings = {};
  settings.sigma.x() = -0.1;
  EXPECT_THROW(Turbulence{settings}, Error);
}

TEST(DiscreteGust, IsOneMinusCosineOverItsDuration) {
  const std::vector<DiscreteGust> gusts = {{1, 3.0, 2.0, 0.5}, {2, -1.0, 2.1, 1.0}};
  EXPECT_EQ(discrete_gust_wind(gusts, 1.99), Eigen::Vector3d::Zero());
  EXPECT_NEAR(discrete_gust_wind(gusts, 2.25).y(), 3.0, 1e-12);  // the peak at mid-duration
  EXPECT_NEAR(discrete_gust_wind(gusts, 2.125).y(), 1.5, 1e-12);
  EXPECT_NEAR(discrete_gust_wind(gusts, 2.6).z(), -1.0, 1e-12);
  EXPECT_NEAR(discrete_gust_wind(gusts, 2.5).y(), 0.0, 1e-12);
  EXPECT_EQ(discrete_gust_wind(gusts, 3.2), Eigen::Vector3d::Zero());
  EXPECT_THROW((DiscreteGust{3, 1.0, 0.0, 1.0}.validate()), Error);
  EXPECT_THROW((DiscreteGust{0, 1.0, 0.0, 0.0}.validate()), Error);
}

}  // namespace
}  // namespace thetad::sim
