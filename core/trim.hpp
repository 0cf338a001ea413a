#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "core/helicopter/helicopter.hpp"

namespace thetad {

// A commanded steady, straight flight: the helicopter moves with a constant inertial velocity at a
// constant attitude, body rates zero. Hover is velocity_ned = 0.
struct TrimCondition {
  Eigen::Vector3d position_ned = Eigen::Vector3d::Zero();  // x_p, y_p, z_p (m); altitude h = -z_p
  Eigen::Vector3d velocity_ned = Eigen::Vector3d::Zero();  // V_N, V_E, V_D (m/s); climb rate = -V_D
  double heading = 0.0;                                    // psi (rad)

  // Hover at altitude h (m) with heading psi.
  static TrimCondition hover(double altitude, double heading = 0.0);
  // Straight flight with ground speed `speed` (m/s) along `course` (rad from north, so course 0 at
  // heading 0 is forward flight, pi/2 sideways to the right, pi rearward) and `climb_rate` (m/s,
  // up positive), at altitude h (m) and heading psi (rad).
  static TrimCondition straight(double speed, double course, double climb_rate, double altitude,
                                double heading = 0.0);
};

// An equilibrium of the helicopter for a TrimCondition.
struct Trim {
  Eigen::VectorXd state;   // 18-state xa: the commanded position and heading, s = 1, integral states 0
  Eigen::VectorXd input;   // [T_mr, delta_ped, delta_col, delta_lon, delta_lat]
  double rotor_speed = 0;  // Omega_mr at the trim (rad/s)
  double residual = 0;     // || f(x, u)[0..13] - [V_ned; 0] ||_2: distance from the commanded motion
  std::string solver_status;  // Ipopt's ApplicationReturnStatus name
  int iterations = 0;         // Ipopt iterations
};

struct TrimOptions {
  double residual_tolerance = 1e-8;  // largest accepted Trim::residual
  int max_iterations = 200;          // Ipopt max_iter
  // Start from this trim's attitude, flapping and inputs instead of the hover guess (T_mr = m g,
  // everything else 0); for sweeps over speed, where the neighbouring trim is much closer.
  std::optional<Trim> initial_guess;
};

// The trim of `plant` (with its current Environment, so a wind is trimmed against) for `condition`,
// by a 9-unknown NLP solved with Ipopt (see trim.cpp). Solves are serialized (Ipopt with MUMPS is
// not thread-safe). Throws thetad::Error naming Ipopt's status and the final constraint violation
// when Ipopt does not converge, or when the equilibrium it returns misses residual_tolerance.
Trim find_trim(const heli::Helicopter& plant, const TrimCondition& condition, const TrimOptions& options = {});

}  // namespace thetad
