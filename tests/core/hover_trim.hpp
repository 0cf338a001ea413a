#pragma once

// The hover trim at h = 3.5 m (resolved preset) as printed in docs/model.md §13, and the point it
// holds: the start and the command of the simulator's tests.

#include <Eigen/Core>

#include "core/control_law.hpp"
#include "core/helicopter/state.hpp"

namespace thetad::testing {

inline Eigen::VectorXd hover_trim_state() {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(heli::kStateDim);
  x[heli::kZp] = -3.5;
  x[heli::kPhi] = 0.084647;
  x[heli::kB1] = 0.0081850;
  x[heli::kS] = 1.0;
  return x;
}

inline Eigen::VectorXd hover_trim_input() {
  Eigen::VectorXd u(heli::kInputDim);
  u << 80.4781, -0.168466, 0.0, 0.0, 0.0018380;
  return u;
}

inline const FixedPosition kHoverPoint(Eigen::Vector3d(0.0, 0.0, -3.5));

}  // namespace thetad::testing
