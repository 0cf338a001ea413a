#include "core/sim/servo_dynamics.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace thetad::sim {

void ServoSettings::validate() const {
  if (delay_samples < 0 || delay_samples > kMaxDelaySamples)
    throw Error("servos: the delay must be 0 to " + std::to_string(kMaxDelaySamples) + " controller samples");
  for (int k = 0; k < time_constant.size(); ++k) {
    if (!(time_constant[k] >= 0.0) || !std::isfinite(time_constant[k]))
      throw Error("servos: input " + std::to_string(k) + ": the time constant must be finite and >= 0");
  }
}

TransportDelay::TransportDelay(Eigen::Index inputs, int samples) : line_(inputs, samples + 1) {
  if (samples < 0) throw Error("transport delay: the delay must be >= 0 samples");
}

void TransportDelay::apply(Eigen::Ref<Eigen::VectorXd> input) {
  if (first_) line_.colwise() = input;
  first_ = false;
  line_.col(next_) = input;
  next_ = (next_ + 1) % line_.cols();
  input = line_.col(next_);
}

ServoLag::ServoLag(const Eigen::VectorXd& time_constants, double period)
    : decay_(time_constants.size()), mean_gain_(time_constants.size()), position_(time_constants.size()) {
  if (!(period > 0.0)) throw Error("servo lag: the period must be positive");
  for (Eigen::Index k = 0; k < time_constants.size(); ++k) {
    const double tau = time_constants[k];
    if (!(tau >= 0.0) || !std::isfinite(tau)) throw Error("servo lag: the time constants must be finite and >= 0");
    decay_[k] = tau > 0.0 ? std::exp(-period / tau) : 0.0;
    mean_gain_[k] = tau > 0.0 ? -std::expm1(-period / tau) * tau / period : 0.0;
  }
  position_.setZero();
}

void ServoLag::apply(Eigen::Ref<Eigen::VectorXd> input) {
  if (first_) position_ = input;
  first_ = false;
  for (Eigen::Index k = 0; k < input.size(); ++k) {
    const double command = input[k], offset = position_[k] - command;
    position_[k] = command + offset * decay_[k];
    input[k] = command + offset * mean_gain_[k];
  }
}

}  // namespace thetad::sim
