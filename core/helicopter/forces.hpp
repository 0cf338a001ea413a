#pragma once

#include <Eigen/Core>

#include "core/helicopter/dual.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/helicopter/model_options.hpp"
#include "core/helicopter/parameters.hpp"

namespace thetad::heli {

// Attitude and air-relative velocity at a state: everything that comes before the rotor speed
// (docs/model.md §3.7 step 1). In double, or in Dual for the Jacobian.
template <class T>
struct BasicAirData {
  T sin_phi, cos_phi, sin_theta, cos_theta, tan_theta, sec_theta;
  Eigen::Matrix<T, 3, 3> rotation;  // R(Theta), body -> NED, Eq. (2)
  T u_a, v_a, w_a;                  // air-relative body velocity (§2.7.1), wind rotated and scaled
};
using AirData = BasicAirData<double>;

// Every auxiliary quantity of one right-hand side (docs/model.md §4, §3.7 steps 2-6), computed once and
// shared by Helicopter::f (which assembles Eqs. 1-9) and Helicopter::sdc (which places the same
// numbers into F and B), so the two cannot disagree about the physics. In double, or in Dual for
// Helicopter::jacobian, which differentiates the same code.
template <class T>
struct BasicForces {
  BasicAirData<T> air;
  T rotor_speed;            // Omega_mr (rad/s)
  T advance_ratio;          // mu (A5)
  T inflow_normal;          // mu_z (A6)
  T induced_main;           // V_imr in effect (m/s): model times the environment factor
  T induced_tail;           // V_itr in effect (m/s)
  T wake_factor;            // K_lambda (A1-A3)
  T x_fus, y_fus, z_fus;    // fuselage forces (A7-A9), N
  T y_tr;                   // velocity part of the tail-rotor side force, m Y_v^tr v_tr, N
  T y_vf;                   // vertical-fin side force after the stall clamp, N
  T z_ht;                   // horizontal-tail force after the stall clamp, N
  T l_tr, n_tr;             // tail-rotor roll and yaw moments (App. B), N m
  T l_vf, n_vf;             // fin roll and yaw moments, N m
  T m_ht;                   // horizontal-tail pitch moment, N m
  T thrust_coefficient;     // C_T
  T torque_coefficient;     // C_Qmr
  T q_mr;                   // main-rotor torque, N m
  T q_tr;                   // tail-rotor torque, N m
  T yaw_inertia;            // I_zz,eff of the explicit r-equation, kg m^2
  // Flapping, Eq. (6) resolved form (§2.5): the speed terms that are not inputs (bias, col. 18),
  // and the coefficients of delta_col, delta_lon, delta_lat.
  T a1_speed, b1_speed;                // [K_z w_a + c_col0 u_a]/(tau_e Omega R), s_b c_col0 v_a/(...)
  T a1_per_collective, b1_per_collective;  // 8 K_mu u_a/(3 tau_e Omega R), s_b 8 K_mu v_a/(...)
  T a1_per_lon, b1_per_lat;            // (A^nom/tau_e)(Omega/Omega_nom)^2, (B^nom/tau_e)(...)^2
};
using Forces = BasicForces<double>;

// The air data at state x (18 entries; only u..psi are read). Throws thetad::Error when |theta|
// exceeds 85 degrees (docs/model.md §3.4) or is not finite.
AirData air_data(const Environment& environment, const Eigen::Ref<const Eigen::VectorXd>& x);

// The forces and moments at state x for main-rotor speed rotor_speed (> 0, else thetad::Error).
Forces evaluate_forces(const Parameters& p, const ModelOptions& options, const Environment& environment,
                       const AirData& air, const Eigen::Ref<const Eigen::VectorXd>& x, double rotor_speed);

// The same two in Dual numbers: what Helicopter::jacobian differentiates.
BasicAirData<Dual> dual_air_data(const Environment& environment, const DualState& x);
BasicForces<Dual> dual_forces(const Parameters& p, const ModelOptions& options, const Environment& environment,
                              const BasicAirData<Dual>& air, const DualState& x, const Dual& rotor_speed);

}  // namespace thetad::heli
