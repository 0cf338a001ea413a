#include "core/helicopter/parameters.hpp"

#include <numbers>

namespace thetad::heli {

Parameters Parameters::nominal() {
  Parameters p{};
  p.mass = 8.2;
  p.gravity = 9.81;
  p.ixx = 0.18;
  p.iyy = 0.34;
  p.izz = 0.28;
  p.i_beta = 0.038;
  p.k_beta = 54.0;
  p.k_mu = 0.2;
  p.tau_e = 0.1;
  p.a_lon_nom = 4.2;
  p.b_lat_nom = 4.2;
  p.lift_slope_mr = 5.5;
  p.lift_slope_tr = 5.0;
  p.chord_mr = 0.058;
  p.chord_tr = 0.029;
  p.radius_mr = 0.775;
  p.radius_tr = 0.13;
  p.cd0_mr = 0.024;
  p.cd0_tr = 0.024;
  p.ct_max_mr = 0.0055;
  p.solidity_nomenclature = 0.0361;
  p.lambda0 = 0.033;
  p.eta_w = 0.9;
  p.omega_nom = 167.0;
  p.gear_tr = 4.66;
  p.h_mr = 0.235;
  p.h_tr = 0.08;
  p.l_tr = 0.91;
  p.l_ht = 0.71;
  p.cd_x = 0.1;
  p.cd_y = 0.5;
  p.cd_z = 0.2;
  p.s_fus_x = 0.1;
  p.s_fus_y = 0.22;
  p.s_fus_z = 0.15;
  p.s_ht = 0.01;
  p.s_vf = 0.012;
  p.cla_ht = 3.0;
  p.cla_vf = 2.0;
  p.eps_vf_tr = 0.2;
  p.v_imr = 4.2;
  p.v_itr = 0.42;
  p.y_ped_tr = 5.4;
  p.y_v_tr = 0.06;
  p.rho = 1.225;
  p.k_s = 0.1;
  p.collective_trim_offset = 0.0944;
  return p;
}

double Parameters::solidity(ModelOptions::Solidity which) const {
  return which == ModelOptions::Solidity::computed ? 2.0 * chord_mr / (std::numbers::pi * radius_mr)
                                                   : solidity_nomenclature;
}

double Parameters::rotor_inertia() const { return 2.5 * i_beta; }

double Parameters::effective_yaw_inertia(ModelOptions::YawInertia which) const {
  switch (which) {
    case ModelOptions::YawInertia::minus_rotor: return izz - rotor_inertia();
    case ModelOptions::YawInertia::izz: return izz;
    case ModelOptions::YawInertia::plus_rotor: return izz + rotor_inertia();
  }
  return izz;  // unreachable: every enumerator is handled above
}

double Parameters::wake_skew_start() const { return (l_tr - radius_mr - radius_tr) / h_tr; }

double Parameters::wake_skew_end() const { return (l_tr - radius_mr + radius_tr) / h_tr; }

double Parameters::tail_rotor_solidity() const { return 2.0 * chord_tr / (std::numbers::pi * radius_tr); }

double Parameters::max_main_rotor_thrust() const {
  const double tip_speed = omega_nom * radius_mr;
  return ct_max_mr * rho * std::numbers::pi * radius_mr * radius_mr * tip_speed * tip_speed;
}

double Parameters::trim_collective(const ModelOptions& options) const {
  return options.collective_trim_offset ? collective_trim_offset : 0.0;
}

}  // namespace thetad::heli
