#include "core/sim/noise.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/helicopter/state.hpp"
#include "core/helicopter/uncertainty.hpp"

namespace thetad::sim {
namespace {

using namespace heli;

constexpr int kDraws = 20000;
// Sample sigma of kDraws normals: relative standard error 1/sqrt(2 N) = 0.5 %; bound 4 errors.
const double kSigmaTolerance = 4.0 / std::sqrt(2.0 * kDraws);

TEST(NoiseLevels, AreTheUncertaintyTablePercents) {
  const NoiseLevels levels = NoiseLevels::from_uncertainty_table();
  const auto measurement = measurement_noise_percents();
  for (int i = 0; i < kPhysicalStateDim; ++i) EXPECT_EQ(levels.measurement[i], measurement[i] / 100.0) << i;
  const auto actuator = actuator_noise_percents();
  for (int i = 0; i < kInputDim; ++i) EXPECT_EQ(levels.actuator[i], actuator[i] / 100.0) << i;
  const auto wind = wind_noise_percents();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(levels.wind_body[i], wind[i] / 100.0) << i;
  const auto induced = induced_velocity_noise_percents();
  EXPECT_EQ(levels.induced_main, induced[0] / 100.0);
  EXPECT_EQ(levels.induced_tail, induced[1] / 100.0);
}

TEST(NoiseLevels, ScaleMultipliesEveryLevel) {
  const NoiseLevels paper = NoiseLevels::from_uncertainty_table();
  const NoiseLevels tripled = NoiseLevels::from_uncertainty_table(3.0);
  EXPECT_EQ(tripled.measurement, 3.0 * paper.measurement);
  EXPECT_EQ(tripled.actuator, 3.0 * paper.actuator);
  EXPECT_EQ(tripled.wind_body, 3.0 * paper.wind_body);
  EXPECT_EQ(tripled.induced_main, 3.0 * paper.induced_main);
  EXPECT_EQ(tripled.induced_tail, 3.0 * paper.induced_tail);
  EXPECT_TRUE(NoiseLevels::from_uncertainty_table(0.0).measurement.isZero());
}

TEST(SampleDraws, TakesNormalPairsInTheDocumentedOrder) {
  std::mt19937_64 rng(3), replay(3);
  SampleDraws draws;
  draws.draw(rng);
  Eigen::Matrix<double, SampleDraws::kCount, 1> expected;
  for (int i = 0; i < SampleDraws::kCount; i += 2) expected.segment<2>(i) = standard_normal_pair(replay);
  EXPECT_EQ(draws.measurement, expected.segment<14>(0));
  EXPECT_EQ(draws.actuator, expected.segment<5>(14));
  EXPECT_EQ(draws.gust, expected.segment<2>(19));
  EXPECT_EQ(draws.wind_body, expected.segment<3>(21));
  EXPECT_EQ(draws.induced_main, expected[24]);
  EXPECT_EQ(draws.induced_tail, expected[25]);
  EXPECT_EQ(rng, replay);
}

TEST(StandardNormal, HasZeroMeanAndUnitSigma) {
  std::mt19937_64 rng(5);
  double sum = 0.0, square_sum = 0.0;
  for (int i = 0; i < kDraws / 2; ++i) {
    const Eigen::Vector2d n = standard_normal_pair(rng);
    sum += n.sum();
    square_sum += n.squaredNorm();
  }
  const double mean = sum / kDraws;
  EXPECT_NEAR(mean, 0.0, 4.0 / std::sqrt(kDraws));
  EXPECT_NEAR(std::sqrt(square_sum / kDraws - mean * mean), 1.0, kSigmaTolerance);
}

// Over many draws, (measured - true)/true per entry has the sigma of the table; entries whose
// signal is 0 are never perturbed.
TEST(Measure, NoiseSigmaIsProportionalToTheFedBackSignalAndZeroAtZero) {
  const NoiseLevels levels = NoiseLevels::from_uncertainty_table();
  const NoiseSettings settings;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kStateDim);
  x << 3.0, -1.0, -3.5, 2.0, 0.0, -0.5, 0.1, 0.0, -0.2, 0.3, 1.5, 0.0, 0.01, -0.004, 7.0, 8.0, 9.0, 0.9;
  const Eigen::Vector3d reference(1.0, -1.0, -2.0);  // y error is 0: no noise on y
  const Eigen::Vector3d integral(0.25, -0.5, 0.75);
  std::mt19937_64 rng(9);
  SampleDraws draws;
  Eigen::VectorXd measured(kStateDim);
  Eigen::VectorXd relative_square_sum = Eigen::VectorXd::Zero(kPhysicalStateDim);
  Eigen::VectorXd signal(kPhysicalStateDim);
  signal << x.head<3>() - reference, x.segment<11>(kU);
  for (int k = 0; k < kDraws; ++k) {
    draws.draw(rng);
    measure(x, reference, integral, draws, levels, settings, measured);
    for (int i = 0; i < kPhysicalStateDim; ++i) {
      const double measured_signal = i < 3 ? measured[i] - reference[i] : measured[i];
      if (signal[i] == 0.0) {
        ASSERT_EQ(measured_signal, 0.0) << "entry " << i;
      } else {
        relative_square_sum[i] += std::pow(measured_signal / signal[i] - 1.0, 2);
      }
    }
    ASSERT_EQ(measured.segment<3>(kXi), integral);
    ASSERT_EQ(measured[kS], 1.0);
  }
  for (int i = 0; i < kPhysicalStateDim; ++i) {
    if (signal[i] == 0.0) continue;
    const double sigma = std::sqrt(relative_square_sum[i] / kDraws);
    EXPECT_NEAR(sigma / levels.measurement[i], 1.0, kSigmaTolerance) << "entry " << i;
  }
}

TEST(Measure, AbsoluteStateReadingScalesThePositionsThemselves) {
  const NoiseLevels levels = NoiseLevels::from_uncertainty_table();
  NoiseSettings settings;
  settings.measurement_on = MeasurementNoiseOn::absolute_state;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kStateDim);
  x.head<3>() << 2.0, 0.0, -3.5;
  std::mt19937_64 rng(13);
  SampleDraws draws;
  draws.draw(rng);
  Eigen::VectorXd measured(kStateDim);
  // Reference at the true position: the feedback-signal reading would be noise-free here.
  measure(x, x.head<3>(), Eigen::Vector3d::Zero(), draws, levels, settings, measured);
  for (int i = 0; i < 3; ++i)
    EXPECT_DOUBLE_EQ(measured[i], x[i] * (1.0 + levels.measurement[i] * draws.measurement[i])) << i;
  settings.measurement_on = MeasurementNoiseOn::feedback_signal;
  measure(x, x.head<3>(), Eigen::Vector3d::Zero(), draws, levels, settings, measured);
  EXPECT_EQ(measured.head<3>(), x.head<3>());
}

TEST(Measure, SwitchedOffPassesTheStateThrough) {
  NoiseSettings settings;
  settings.measurement = false;
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(kStateDim, 1.0, 18.0);
  std::mt19937_64 rng(17);
  SampleDraws draws;
  draws.draw(rng);
  Eigen::VectorXd measured(kStateDim);
  measure(x, Eigen::Vector3d(5, 5, 5), Eigen::Vector3d::Zero(), draws, NoiseLevels::from_uncertainty_table(),
          settings, measured);
  EXPECT_EQ(measured.head<kPhysicalStateDim>(), x.head<kPhysicalStateDim>());
}

TEST(ActuatorNoise, SigmaIsProportionalToTheCommandAndZeroAtZero) {
  const NoiseLevels levels = NoiseLevels::from_uncertainty_table();
  const NoiseSettings settings;
  Eigen::VectorXd command(kInputDim);
  command << 80.0, -0.17, 0.0, 0.02, -0.003;
  Eigen::VectorXd applied(kInputDim);
  Eigen::VectorXd relative_square_sum = Eigen::VectorXd::Zero(kInputDim);
  std::mt19937_64 rng(19);
  SampleDraws draws;
  for (int k = 0; k < kDraws; ++k) {
    draws.draw(rng);
    apply_actuator_noise(command, draws, levels, settings, applied);
    ASSERT_EQ(applied[kCol], 0.0);
    for (int i = 0; i < kInputDim; ++i)
      if (command[i] != 0.0) relative_square_sum[i] += std::pow(applied[i] / command[i] - 1.0, 2);
  }
  for (int i = 0; i < kInputDim; ++i) {
    if (command[i] == 0.0) continue;
    EXPECT_NEAR(std::sqrt(relative_square_sum[i] / kDraws) / levels.actuator[i], 1.0, kSigmaTolerance) << i;
  }
  NoiseSettings off;
  off.actuator = false;
  apply_actuator_noise(command, draws, levels, off, applied);
  EXPECT_EQ(applied, command);
}

TEST(Environment, ScalesWindAndInducedVelocitiesByTheTableLevels) {
  const NoiseLevels levels = NoiseLevels::from_uncertainty_table();
  const NoiseSettings settings;
  const Eigen::Vector3d wind(1.7, -0.2, 0.0);
  Eigen::Vector3d wind_scale_square = Eigen::Vector3d::Zero();
  double main_square = 0.0, tail_square = 0.0;
  std::mt19937_64 rng(23);
  SampleDraws draws;
  for (int k = 0; k < kDraws; ++k) {
    draws.draw(rng);
    const Environment environment = sample_environment(wind, draws, levels, settings);
    ASSERT_EQ(environment.wind_ned, wind);
    wind_scale_square += (environment.wind_body_scale.array() - 1.0).square().matrix();
    main_square += std::pow(environment.induced_main_scale - 1.0, 2);
    tail_square += std::pow(environment.induced_tail_scale - 1.0, 2);
  }
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(std::sqrt(wind_scale_square[i] / kDraws) / levels.wind_body[i], 1.0, kSigmaTolerance) << i;
  EXPECT_NEAR(std::sqrt(main_square / kDraws) / levels.induced_main, 1.0, kSigmaTolerance);
  EXPECT_NEAR(std::sqrt(tail_square / kDraws) / levels.induced_tail, 1.0, kSigmaTolerance);

  NoiseSettings off;
  off.wind_component = false;
  off.induced_velocity = false;
  const Environment nominal = sample_environment(wind, draws, levels, off);
  EXPECT_EQ(nominal.wind_body_scale, Eigen::Vector3d::Ones());
  EXPECT_EQ(nominal.induced_main_scale, 1.0);
  EXPECT_EQ(nominal.induced_tail_scale, 1.0);
}

}  // namespace
}  // namespace thetad::sim
