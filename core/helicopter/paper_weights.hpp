#pragma once

#include <Eigen/Core>

namespace thetad::heli {

// The paper's weights, Eqs. (33)-(34) with the lost exponents read as powers of ten (docs/model.md §7,
// The state order is that of V_track (Eq. 36); the bias state s is not penalized.
inline Eigen::VectorXd paper_state_weights() {
  Eigen::VectorXd q(18);
  q << 1e4, 2e4, 1e7,       // x_p, y_p, z_p
      100, 100, 1,          // u, v, w
      100, 100, 1e3,        // phi, theta, psi
      200, 1, 200,          // p, q, r
      1e5, 1e5,             // a1, b1
      2e3, 2e3, 1e6,        // x_i, y_i, z_i
      0;                    // s
  return q;
}

inline Eigen::VectorXd paper_input_weights() {
  Eigen::VectorXd r(5);
  r << 1, 200, 1e7, 1e5, 1e5;  // T_mr, delta_ped, delta_col, delta_lon, delta_lat
  return r;
}

}  // namespace thetad::heli
