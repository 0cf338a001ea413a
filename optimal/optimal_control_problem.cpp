#include "optimal/optimal_control_problem.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace thetad {

int OptimalControlProblem::node_dim() const {
  return plant->state_dim() + (sampled_position_integral ? 3 : 0);
}

void OptimalControlProblem::validate() const {
  const auto fail = [](const std::string& why) { throw Error("optimal control problem: " + why); };
  if (plant == nullptr) fail("no plant");
  if (reference == nullptr) fail("no reference trajectory");
  const int n = plant->state_dim(), m = plant->input_dim();
  const auto sized = [&](const Eigen::VectorXd& v, int size, const char* name) {
    if (v.size() != size)
      fail(std::string(name) + " has " + std::to_string(v.size()) + " entries, the plant needs " + std::to_string(size));
    if (!v.allFinite()) fail(std::string(name) + " is not finite");
  };
  sized(initial_state, n, "initial_state");
  sized(state_weights, n, "state_weights");
  sized(input_weights, m, "input_weights");
  if (input_lower.size() != 0 || input_upper.size() != 0) {
    sized(input_lower, m, "input_lower");
    sized(input_upper, m, "input_upper");
    if ((input_lower.array() > input_upper.array()).any()) fail("input_lower exceeds input_upper");
  }
  if (deviation_trims && plant->bias_state() < 0) fail("J_dev needs a plant with a bias state (SdcPlant::bias_state)");
  if ((state_weights.array() < 0.0).any() || (input_weights.array() < 0.0).any())
    fail("the weights must be non-negative");
  if (!(dt > 0.0) || !std::isfinite(dt)) fail("dt must be positive and finite");
  if (controller_period_steps < 1) fail("controller_period_steps must be at least 1");
  if (interval_periods < 1) fail("interval_periods must be at least 1");
  if (intervals < 1) fail("intervals must be at least 1");
  if (first_sample < 0) fail("first_sample must not be negative");
  if (!initial_integral.allFinite()) fail("initial_integral is not finite");
  if (sampled_position_integral && (*sampled_position_integral < 3 || *sampled_position_integral + 3 > n))
    fail("sampled_position_integral " + std::to_string(*sampled_position_integral) +
         " leaves no room for three integral entries after the position x[0..2] in " + std::to_string(n) + " states");
}

}  // namespace thetad
