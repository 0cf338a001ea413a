#pragma once

#include <cstdint>
#include <random>

#include <Eigen/Core>

namespace thetad::sim {

using SensedVector = Eigen::Matrix<double, 14, 1>;

// Additive sensor noise in physical units (docs/model.md §15.4), besides the paper's relative 5 %:
// on the 14 sensed states x_p, y_p, z_p (m), u, v, w (m/s), φ, θ, ψ (rad), p, q, r (rad/s), a1, b1
// (rad). Each channel's noise is white with the one-sided density `density` (unit/√Hz): its PSD
// density² (unit²/Hz) is flat to the Nyquist frequency of the controller's sampling, so a sample's
// standard deviation is density √(f_s / 2) and the power in any band below f_s / 2 is the same at
// every controller rate. `bias` is the standard deviation of a constant offset per channel, drawn
// once per run. Zero (the default) everywhere: off.
struct SensorNoiseSettings {
  SensedVector density = SensedVector::Zero();
  SensedVector bias = SensedVector::Zero();

  bool active() const { return (density.array() != 0.0).any() || (bias.array() != 0.0).any(); }
  // Throws thetad::Error naming the first channel that is negative or not finite.
  void validate() const;
};

// The noise of SensorNoiseSettings, per controller sample from its own generator
// (RandomStream::sensor_noise; the biases from RandomStream::sensor_bias). Allocates nothing.
class SensorNoise {
 public:
  SensorNoise(const SensorNoiseSettings& settings, double sample_period);

  // The run's start: generators seeded, biases drawn.
  void start(std::uint64_t run_seed);
  // Adds one sample's noise and the run's biases to the 14 sensed entries.
  void add(Eigen::Ref<SensedVector> sensed);
  const SensedVector& biases() const { return biases_; }
  // Standard deviation of one sample's noise per channel.
  const SensedVector& sample_sigma() const { return sample_sigma_; }

 private:
  SensorNoiseSettings settings_;
  SensedVector sample_sigma_;
  SensedVector biases_ = SensedVector::Zero();
  std::mt19937_64 rng_;
};

}  // namespace thetad::sim
