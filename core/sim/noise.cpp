#include "core/sim/noise.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include "core/helicopter/state.hpp"
#include "core/helicopter/uncertainty.hpp"

namespace thetad::sim {

namespace {

// Uniform in (0, 1]: the top 53 bits of one engine output, shifted by one ulp so log() is finite.
double uniform_open_closed(std::mt19937_64& rng) {
  constexpr double kScale = 1.0 / 9007199254740992.0;  // 2^-53
  return (static_cast<double>(rng() >> 11) + 1.0) * kScale;
}

template <std::size_t N>
Eigen::Matrix<double, static_cast<int>(N), 1> fractions(const std::array<double, N>& percents) {
  Eigen::Matrix<double, static_cast<int>(N), 1> f;
  for (std::size_t i = 0; i < N; ++i) f[static_cast<Eigen::Index>(i)] = percents[i] / 100.0;
  return f;
}

}  // namespace

Eigen::Vector2d standard_normal_pair(std::mt19937_64& rng) {
  const double radius = std::sqrt(-2.0 * std::log(uniform_open_closed(rng)));
  const double angle = 2.0 * std::numbers::pi * uniform_open_closed(rng);
  return {radius * std::cos(angle), radius * std::sin(angle)};
}

void SampleDraws::draw(std::mt19937_64& rng) {
  static_assert(kCount % 2 == 0, "draws are taken in Box-Muller pairs");
  std::array<double, kCount> n;
  for (int i = 0; i < kCount; i += 2) {
    const Eigen::Vector2d pair = standard_normal_pair(rng);
    n[i] = pair.x();
    n[i + 1] = pair.y();
  }
  int next = 0;
  for (int i = 0; i < measurement.size(); ++i) measurement[i] = n[next++];
  for (int i = 0; i < actuator.size(); ++i) actuator[i] = n[next++];
  for (int i = 0; i < gust.size(); ++i) gust[i] = n[next++];
  for (int i = 0; i < wind_body.size(); ++i) wind_body[i] = n[next++];
  induced_main = n[next++];
  induced_tail = n[next++];
}

NoiseLevels NoiseLevels::from_uncertainty_table(double scale) {
  NoiseLevels levels;
  levels.measurement = scale * fractions(heli::measurement_noise_percents());
  levels.actuator = scale * fractions(heli::actuator_noise_percents());
  levels.wind_body = scale * fractions(heli::wind_noise_percents());
  const auto induced = fractions(heli::induced_velocity_noise_percents());
  levels.induced_main = scale * induced[0];
  levels.induced_tail = scale * induced[1];
  return levels;
}

void measure(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Vector3d& reference_position,
             const Eigen::Vector3d& measured_position_integral, const SampleDraws& draws,
             const NoiseLevels& levels, const NoiseSettings& settings, Eigen::Ref<Eigen::VectorXd> measured) {
  using namespace heli;
  measured.head<kPhysicalStateDim>() = x.head<kPhysicalStateDim>();
  if (settings.measurement) {
    const auto factor = (1.0 + levels.measurement.array() * draws.measurement.array()).matrix();
    const Eigen::Vector3d position = x.segment<3>(kXp);
    if (settings.measurement_on == MeasurementNoiseOn::feedback_signal) {
      measured.segment<3>(kXp) =
          reference_position + ((position - reference_position).array() * factor.head<3>().array()).matrix();
    } else {
      measured.segment<3>(kXp) = (position.array() * factor.head<3>().array()).matrix();
    }
    measured.segment<11>(kU) = (x.segment<11>(kU).array() * factor.tail<11>().array()).matrix();
  }
  measured.segment<3>(kXi) = measured_position_integral;
  measured[kS] = 1.0;
}

void apply_actuator_noise(const Eigen::Ref<const Eigen::VectorXd>& command, const SampleDraws& draws,
                          const NoiseLevels& levels, const NoiseSettings& settings,
                          Eigen::Ref<Eigen::VectorXd> applied) {
  if (settings.actuator) {
    applied = (command.array() * (1.0 + levels.actuator.array() * draws.actuator.array())).matrix();
  } else {
    applied = command;
  }
}

heli::Environment sample_environment(const Eigen::Vector3d& wind_ned, const SampleDraws& draws,
                                     const NoiseLevels& levels, const NoiseSettings& settings) {
  heli::Environment environment;
  environment.wind_ned = wind_ned;
  if (settings.wind_component) {
    environment.wind_body_scale = (1.0 + levels.wind_body.array() * draws.wind_body.array()).matrix();
  }
  if (settings.induced_velocity) {
    environment.induced_main_scale = 1.0 + levels.induced_main * draws.induced_main;
    environment.induced_tail_scale = 1.0 + levels.induced_tail * draws.induced_tail;
  }
  return environment;
}

}  // namespace thetad::sim
