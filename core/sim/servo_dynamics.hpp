#pragma once

#include <Eigen/Core>

#include "core/sim/actuator_limits.hpp"

namespace thetad::sim {

// What the servos add between the controller and the limits (docs/model.md §15.5): a transport
// delay of the command in whole controller samples, and a first-order lag per input. The chain is
// delay, actuator noise, lag, rate limit, magnitude limit. Zero (the default): neither.
struct ServoSettings {
  InputVector time_constant = InputVector::Zero();  // s, per input; 0: no lag
  int delay_samples = 0;                            // controller samples

  bool lagged() const { return (time_constant.array() != 0.0).any(); }
  bool active() const { return delay_samples > 0 || lagged(); }
  // Throws thetad::Error naming the first setting out of range.
  void validate() const;
  // A delay beyond this (about a minute at 1 kHz) is a mistake, not a study.
  static constexpr int kMaxDelaySamples = 65536;
};

// The command of `samples` controller samples ago; until that many have been given, the first
// (the servos hold it until the first delayed command arrives). Any number of inputs; allocates
// only at construction.
class TransportDelay {
 public:
  TransportDelay(Eigen::Index inputs, int samples);

  void reset() { first_ = true; }
  // Replaces `input` by the delayed one.
  void apply(Eigen::Ref<Eigen::VectorXd> input);

 private:
  Eigen::MatrixXd line_;  // one column per sample held, a ring
  Eigen::Index next_ = 0;
  bool first_ = true;
};

// First-order lags τ y' = u - y with the command u held over each controller period T. The
// servo's position at the samples is exact (y_{k+1} = u + (y_k - u) e^{-T/τ}); what the plant
// receives over the period is its mean, u + (y_k - u) (τ/T)(1 - e^{-T/τ}), so that the held input
// delivers the servo's impulse. The first sample after reset() starts the servos at its command.
// τ = 0: no lag on that input. Allocates only at construction.
class ServoLag {
 public:
  ServoLag(const Eigen::VectorXd& time_constants, double period);

  void reset() { first_ = true; }
  // Replaces `input` by the mean servo position over the coming period.
  void apply(Eigen::Ref<Eigen::VectorXd> input);
  // The servo positions at the end of the period of the last apply().
  const Eigen::VectorXd& position() const { return position_; }

 private:
  Eigen::VectorXd decay_, mean_gain_, position_;
  bool first_ = true;
};

}  // namespace thetad::sim
