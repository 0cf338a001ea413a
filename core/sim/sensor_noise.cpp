#include "core/sim/sensor_noise.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/sim/noise.hpp"
#include "core/sim/seed.hpp"

namespace thetad::sim {

namespace {

// 14 standard normals, in Box-Muller pairs.
SensedVector standard_normals(std::mt19937_64& rng) {
  SensedVector n;
  for (int i = 0; i < n.size(); i += 2) n.segment<2>(i) = standard_normal_pair(rng);
  return n;
}

}  // namespace

void SensorNoiseSettings::validate() const {
  for (int i = 0; i < density.size(); ++i) {
    if (!(density[i] >= 0.0) || !std::isfinite(density[i]) || !(bias[i] >= 0.0) || !std::isfinite(bias[i]))
      throw Error("sensor noise: channel " + std::to_string(i) + ": the density and the bias must be finite and >= 0");
  }
}

SensorNoise::SensorNoise(const SensorNoiseSettings& settings, double sample_period)
    : settings_(settings), sample_sigma_(settings.density / std::sqrt(2.0 * sample_period)) {
  settings_.validate();
  if (!(sample_period > 0.0)) throw Error("sensor noise: the sample period must be positive");
}

void SensorNoise::start(std::uint64_t run_seed) {
  std::mt19937_64 bias_rng(stream_seed(run_seed, RandomStream::sensor_bias));
  biases_ = settings_.bias.cwiseProduct(standard_normals(bias_rng));
  rng_.seed(stream_seed(run_seed, RandomStream::sensor_noise));
}

void SensorNoise::add(Eigen::Ref<SensedVector> sensed) {
  sensed += biases_ + sample_sigma_.cwiseProduct(standard_normals(rng_));
}

}  // namespace thetad::sim
