#include "core/sim/deviation_cost.hpp"

#include <utility>

#include "core/error.hpp"

namespace thetad::sim {

namespace {

TrimPoint zero_point(const SdcPlant& plant) {
  return {Eigen::VectorXd::Zero(plant.state_dim()), Eigen::VectorXd::Zero(plant.input_dim()),
          Eigen::VectorXd::Zero(plant.state_dim())};
}

}  // namespace

DeviationCost::DeviationCost(const SdcPlant& plant, std::shared_ptr<const TrimSource> trims,
                             DeviationWeights weights, double controller_period)
    : motion_(plant, FeedForward::velocity_trim, zero_point(plant), std::move(trims)),
      weights_(std::move(weights)),
      period_(controller_period),
      target_(plant.state_dim()),
      error_(plant.state_dim()),
      input_error_(plant.input_dim()) {
  if (weights_.state.size() != plant.state_dim() || weights_.input.size() != plant.input_dim())
    throw Error("J_dev: the weights have " + std::to_string(weights_.state.size()) + " and " +
                std::to_string(weights_.input.size()) + " entries, the plant needs " +
                std::to_string(plant.state_dim()) + " and " + std::to_string(plant.input_dim()));
}

void DeviationCost::add(const Eigen::Ref<const Eigen::VectorXd>& x, const Reference& reference,
                        const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& u) {
  target(x, reference, error_, input_error_);
  error_ = v - error_;
  input_error_ = u - input_error_;
  sum_ += error_.cwiseAbs2().dot(weights_.state) + input_error_.cwiseAbs2().dot(weights_.input);
}

void DeviationCost::target(const Eigen::Ref<const Eigen::VectorXd>& x, const Reference& reference,
                           Eigen::Ref<Eigen::VectorXd> tracking, Eigen::Ref<Eigen::VectorXd> input) {
  motion_.aim(x, reference);
  // V* = the tracking vector of x_r: the plant's tracking vector is the state less what the
  // reference commands (bias entry 1), so V − V* is x − x_r with the true integral errors.
  target_ = motion_.motion().state;
  target_[motion_.bias_state()] = 1.0;
  motion_.plant().tracking_vector(target_, reference, tracking);
  input = motion_.motion().input;
}

}  // namespace thetad::sim
