#pragma once

#include <Eigen/Core>

namespace thetad::heli {

// The designed weights shipped in scenarios/designed.settings.yaml (`thetad weights`,
// docs/weights.md), as that file writes them: the weights J_dev scores every controller with
// (docs/model.md §7.2). A test keeps the two equal; regenerate both together.
inline Eigen::VectorXd designed_state_weights() {
  Eigen::VectorXd q(18);
  q << 4, 4, 4,                    // x_p, y_p, z_p
      1, 1, 1,                     // u, v, w
      44.4444, 44.4444, 100,       // phi, theta, psi
      4, 4, 4,                     // p, q, r
      400, 400,                    // a1, b1
      1, 1, 1,                     // x_i, y_i, z_i
      0;                           // s
  return q;
}

inline Eigen::VectorXd designed_input_weights() {
  Eigen::VectorXd r(5);
  r << 0.0395261, 4775.42, 39867.4, 1066.22, 1074.27;  // T_mr, delta_ped, delta_col, delta_lon, delta_lat
  return r;
}

}  // namespace thetad::heli
