#include "export/helicopter_constants.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "core/helicopter/rotor_speed.hpp"
#include "export/constant_source.hpp"

namespace thetad {

thetad_onboard::HelicopterConstants onboard_helicopter(const heli::Helicopter& model) {
  const heli::Environment& environment = model.environment();
  if (!(environment.wind_ned.array() == 0.0).all() || !(environment.wind_body_scale.array() == 1.0).all() ||
      environment.induced_main_scale != 1.0 || environment.induced_tail_scale != 1.0)
    throw Error("export: the helicopter model has wind or scaled induced velocities; a controller's model has neither");
  const heli::Parameters& p = model.parameters();
  const heli::ModelOptions& o = model.options();
  using Options = heli::ModelOptions;
  thetad_onboard::HelicopterConstants c{};
  c.mass = p.mass;
  c.gravity = p.gravity;
  c.ixx = p.ixx;
  c.iyy = p.iyy;
  c.izz = p.izz;
  c.yaw_inertia = p.effective_yaw_inertia(o.yaw_inertia);
  c.k_beta = p.k_beta;
  c.k_mu = p.k_mu;
  c.tau_e = p.tau_e;
  c.a_lon_nom = p.a_lon_nom;
  c.b_lat_nom = p.b_lat_nom;
  c.lift_slope_mr = p.lift_slope_mr;
  c.radius_mr = p.radius_mr;
  c.radius_tr = p.radius_tr;
  c.cd0_mr = p.cd0_mr;
  c.cd0_tr = p.cd0_tr;
  c.lambda0 = p.lambda0;
  c.eta_w = p.eta_w;
  c.omega_nom = p.omega_nom;
  c.gear_tr = p.gear_tr;
  c.h_mr = p.h_mr;
  c.h_tr = p.h_tr;
  c.l_tr = p.l_tr;
  c.l_ht = p.l_ht;
  c.cd_x = p.cd_x;
  c.cd_y = p.cd_y;
  c.cd_z = p.cd_z;
  c.s_fus_x = p.s_fus_x;
  c.s_fus_y = p.s_fus_y;
  c.s_fus_z = p.s_fus_z;
  c.s_ht = p.s_ht;
  c.s_vf = p.s_vf;
  c.cla_ht = p.cla_ht;
  c.cla_vf = p.cla_vf;
  c.eps_vf_tr = p.eps_vf_tr;
  c.v_imr = p.v_imr;
  c.v_itr = p.v_itr;
  c.y_ped_tr = p.y_ped_tr;
  c.y_v_tr = p.y_v_tr;
  c.rho = p.rho;
  c.k_s = p.k_s;
  c.solidity = p.solidity(o.solidity);
  c.tail_rotor_solidity = p.tail_rotor_solidity();
  c.trim_collective = p.trim_collective(o);
  c.wake_skew_start = p.wake_skew_start();
  c.wake_skew_end = p.wake_skew_end();
  c.lateral_flap_speed_sign = o.lateral_flap_speed_sign;
  c.fuselage_downwash_sign = o.fuselage_downwash_sign;
  c.tail_rotor_velocity_sign = o.tail_rotor_velocity_sign;
  c.horizontal_tail_sign = o.horizontal_tail_sign;
  c.flap_inflow_sign_from_u_a = o.flap_inflow_sign_source == Options::FlapInflowSignSource::u_a;
  c.rotor_speed_governor = o.rotor_speed_model == Options::RotorSpeedModel::governor;
  c.tail_rotor_profile_torque = o.tail_rotor_torque == Options::TailRotorTorque::profile;
  c.induced_velocity_lambda0 = o.induced_velocity_model == Options::InducedVelocityModel::lambda0_omega_r;
  c.min_rotor_speed = heli::kMinRotorSpeed;
  c.max_rotor_speed = heli::kMaxRotorSpeed;
  c.max_pitch = 85.0 * std::numbers::pi / 180.0;  // forces.cpp's kMaxPitch
  return c;
}

std::string helicopter_constants_source(const thetad_onboard::HelicopterConstants& c, const std::string& name) {
  std::string s = "inline constexpr thetad_onboard::HelicopterConstants " + name + "{\n";
  const auto number = [&s](const char* field, double value) {
    s += "    ." + std::string(field) + " = " + exact_literal(value) + ",\n";
  };
  const auto integer = [&s](const char* field, int value) {
    s += "    ." + std::string(field) + " = " + std::to_string(value) + ",\n";
  };
  number("mass", c.mass);
  number("gravity", c.gravity);
  number("ixx", c.ixx);
  number("iyy", c.iyy);
  number("izz", c.izz);
  number("yaw_inertia", c.yaw_inertia);
  number("k_beta", c.k_beta);
  number("k_mu", c.k_mu);
  number("tau_e", c.tau_e);
  number("a_lon_nom", c.a_lon_nom);
  number("b_lat_nom", c.b_lat_nom);
  number("lift_slope_mr", c.lift_slope_mr);
  number("radius_mr", c.radius_mr);
  number("radius_tr", c.radius_tr);
  number("cd0_mr", c.cd0_mr);
  number("cd0_tr", c.cd0_tr);
  number("lambda0", c.lambda0);
  number("eta_w", c.eta_w);
  number("omega_nom", c.omega_nom);
  number("gear_tr", c.gear_tr);
  number("h_mr", c.h_mr);
  number("h_tr", c.h_tr);
  number("l_tr", c.l_tr);
  number("l_ht", c.l_ht);
  number("cd_x", c.cd_x);
  number("cd_y", c.cd_y);
  number("cd_z", c.cd_z);
  number("s_fus_x", c.s_fus_x);
  number("s_fus_y", c.s_fus_y);
  number("s_fus_z", c.s_fus_z);
  number("s_ht", c.s_ht);
  number("s_vf", c.s_vf);
  number("cla_ht", c.cla_ht);
  number("cla_vf", c.cla_vf);
  number("eps_vf_tr", c.eps_vf_tr);
  number("v_imr", c.v_imr);
  number("v_itr", c.v_itr);
  number("y_ped_tr", c.y_ped_tr);
  number("y_v_tr", c.y_v_tr);
  number("rho", c.rho);
  number("k_s", c.k_s);
  number("solidity", c.solidity);
  number("tail_rotor_solidity", c.tail_rotor_solidity);
  number("trim_collective", c.trim_collective);
  number("wake_skew_start", c.wake_skew_start);
  number("wake_skew_end", c.wake_skew_end);
  number("lateral_flap_speed_sign", c.lateral_flap_speed_sign);
  number("fuselage_downwash_sign", c.fuselage_downwash_sign);
  number("tail_rotor_velocity_sign", c.tail_rotor_velocity_sign);
  number("horizontal_tail_sign", c.horizontal_tail_sign);
  integer("flap_inflow_sign_from_u_a", c.flap_inflow_sign_from_u_a);
  integer("rotor_speed_governor", c.rotor_speed_governor);
  integer("tail_rotor_profile_torque", c.tail_rotor_profile_torque);
  integer("induced_velocity_lambda0", c.induced_velocity_lambda0);
  number("min_rotor_speed", c.min_rotor_speed);
  number("max_rotor_speed", c.max_rotor_speed);
  number("max_pitch", c.max_pitch);
  return s + "};\n";
}

}  // namespace thetad
