#include "core/sim/disturbances.hpp"

#include <cstdio>

namespace thetad::sim {

std::optional<std::string> NoDisturbances::check(const Eigen::VectorXd& x, double t) const {
  char text[120];
  if (!x.allFinite()) {
    std::snprintf(text, sizeof text, "non-finite state at t = %.4f s", t);
    return text;
  }
  const double largest = x.cwiseAbs().maxCoeff();
  if (largest <= max_state_) return std::nullopt;
  std::snprintf(text, sizeof text, "|x|_inf = %.6g exceeds %.6g at t = %.4f s", largest, max_state_, t);
  return text;
}

}  // namespace thetad::sim
