#pragma once

#include "core/helicopter/forces.hpp"
#include "core/helicopter/parameters.hpp"
#include "core/helicopter/state.hpp"

namespace thetad::heli {

// Eqs. 1-9 and 26 (docs/model.md §3.7 step 7): xdot from the state, the input and the forces at them. A
// template over the number type (double for Helicopter::f, Dual for Helicopter::jacobian), so
// that the Jacobian differentiates the very expressions the simulator integrates.
template <class T, class State, class Input, class Derivative>
void equations_of_motion(const Parameters& p, const BasicForces<T>& f, const State& x, const Input& u,
                         Derivative& xdot) {
  const BasicAirData<T>& air = f.air;
  const T thrust = u[kTmr], pedal = u[kPed], collective = u[kCol], lon = u[kLon], lat = u[kLat];
  const double m = p.mass, g = p.gravity;
  const T uu = x[kU], vv = x[kV], ww = x[kW];
  const T pr = x[kP], qr = x[kQ], rr = x[kR];
  const T a1 = x[kA1], b1 = x[kB1];

  xdot.template segment<3>(kXp) = air.rotation * x.template segment<3>(kU);  // Eq. (1)
  // Eq. (3): main-rotor force (-T a1, T b1, -T), tail-rotor pedal force m Y_dped delta_ped.
  xdot[kU] = vv * rr - ww * qr + f.x_fus / m - g * air.sin_theta - a1 * thrust / m;
  xdot[kV] = ww * pr - uu * rr + (f.y_fus + f.y_tr + f.y_vf) / m + g * air.sin_phi * air.cos_theta +
             p.y_ped_tr * pedal + b1 * thrust / m;
  xdot[kW] = uu * qr - vv * pr + f.z_fus / m + g * air.cos_phi * air.cos_theta - thrust / m;
  // Eq. (5).
  xdot[kPhi] = pr + (qr * air.sin_phi + rr * air.cos_phi) * air.tan_theta;
  xdot[kTheta] = qr * air.cos_phi - rr * air.sin_phi;
  xdot[kPsi] = (qr * air.sin_phi + rr * air.cos_phi) * air.sec_theta;
  // Eq. (4); the r-equation solved for r_dot with Q_e of B1.
  const T hub_moment_per_flap = p.k_beta + thrust * p.h_mr;  // L_mr = (.) b1, M_mr = (.) a1
  xdot[kP] = (qr * rr * (p.iyy - p.izz) + f.l_vf + f.l_tr + p.h_tr * m * p.y_ped_tr * pedal + hub_moment_per_flap * b1) / p.ixx;
  xdot[kQ] = (pr * rr * (p.izz - p.ixx) + f.m_ht + hub_moment_per_flap * a1) / p.iyy;
  xdot[kR] = (pr * qr * (p.ixx - p.iyy) + f.n_vf + f.n_tr - f.q_mr - p.gear_tr * f.q_tr - m * p.y_ped_tr * p.l_tr * pedal) /
             f.yaw_inertia;
  // Eq. (6), resolved form of §2.5.
  xdot[kA1] = -qr - a1 / p.tau_e + f.a1_speed + f.a1_per_collective * collective + f.a1_per_lon * lon;
  xdot[kB1] = -pr - b1 / p.tau_e + f.b1_speed + f.b1_per_collective * collective + f.b1_per_lat * lat;
  xdot.template segment<3>(kXi) = x.template segment<3>(kXp);  // Eq. (9)
  xdot[kS] = -p.k_s * x[kS];                                   // Eq. (26)
}

}  // namespace thetad::heli
