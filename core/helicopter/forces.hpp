#pragma once

#include <Eigen/Core>

#include "core/helicopter/helicopter.hpp"
#include "core/helicopter/model_options.hpp"
#include "core/helicopter/parameters.hpp"

namespace thetad::heli {

// Attitude and air-relative velocity at a state: everything that comes before the rotor speed
// (spec §2.9 step 1).
struct AirData {
  double sin_phi, cos_phi, sin_theta, cos_theta, tan_theta, sec_theta;
  Eigen::Matrix3d rotation;  // R(Theta), body -> NED, Eq. (2)
  double u_a, v_a, w_a;      // air-relative body velocity (§2.7.1), wind rotated and scaled
};

// Every auxiliary quantity of one right-hand side (spec §2.7-2.8, §2.9 steps 2-6), computed once and
// shared by Helicopter::f (which assembles Eqs. 1-9) and Helicopter::sdc (which places the same
// numbers into F and B), so the two cannot disagree about the physics.
struct Forces {
  AirData air;
  double rotor_speed;            // Omega_mr (rad/s)
  double advance_ratio;          // mu (A5)
  double inflow_normal;          // mu_z (A6)
  double induced_main;           // V_imr in effect (m/s): model times the environment factor
  double induced_tail;           // V_itr in effect (m/s)
  double wake_factor;            // K_lambda (A1-A3)
  double x_fus, y_fus, z_fus;    // fuselage forces (A7-A9), N
  double y_tr;                   // velocity part of the tail-rotor side force, m Y_v^tr v_tr, N
  double y_vf;                   // vertical-fin side force after the stall clamp, N
  double z_ht;                   // horizontal-tail force after the stall clamp, N
  double l_tr, n_tr;             // tail-rotor roll and yaw moments (App. B), N m
  double l_vf, n_vf;             // fin roll and yaw moments, N m
  double m_ht;                   // horizontal-tail pitch moment, N m
  double thrust_coefficient;     // C_T
  double torque_coefficient;     // C_Qmr
  double q_mr;                   // main-rotor torque, N m
  double q_tr;                   // tail-rotor torque, N m
  double yaw_inertia;            // I_zz,eff of the explicit r-equation, kg m^2
  // Flapping, Eq. (6) resolved form (§2.5): the speed terms that are not inputs (bias, col. 18),
  // and the coefficients of delta_col, delta_lon, delta_lat.
  double a1_speed, b1_speed;                // [K_z w_a + c_col0 u_a]/(tau_e Omega R), s_b c_col0 v_a/(...)
  double a1_per_collective, b1_per_collective;  // 8 K_mu u_a/(3 tau_e Omega R), s_b 8 K_mu v_a/(...)
  double a1_per_lon, b1_per_lat;            // (A^nom/tau_e)(Omega/Omega_nom)^2, (B^nom/tau_e)(...)^2
};

// The air data at state x (18 entries; only u..psi are read). Throws thetad::Error when |theta|
// exceeds 85 degrees (spec §6.5) or is not finite.
AirData air_data(const Environment& environment, const Eigen::Ref<const Eigen::VectorXd>& x);

// The forces and moments at state x for main-rotor speed rotor_speed (> 0, else thetad::Error).
Forces evaluate_forces(const Parameters& p, const ModelOptions& options, const Environment& environment,
                       const AirData& air, const Eigen::Ref<const Eigen::VectorXd>& x, double rotor_speed);

}  // namespace thetad::heli
