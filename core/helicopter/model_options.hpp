#pragma once

#include <array>
#include <string>
#include <string_view>

namespace thetad::heli {

// The model switches of docs/model.md §11: each member is one switch, named as in the spec's table, so that
// the paper-literal text and our resolution of its inconsistencies can both be flown.
// Sign switches hold +1 or -1 and multiply the term they name.
struct ModelOptions {
  enum class FlapInflowSignSource { mu, u_a };                       // sign(mu) == +1 | sign(u_a)
  enum class YawInertia { minus_rotor, izz, plus_rotor };            // I_zz - I_rot | I_zz | I_zz + I_rot
  enum class RotorSpeedModel { thrust_inversion, governor };         // A4 root | Omega_nom
  enum class Solidity { nomenclature, computed };                    // 0.0361 | 2 c_mr/(pi R_mr)
  enum class TailRotorTorque { none, profile };                      // Q_tr = 0 | profile drag
  enum class InducedVelocityModel { constant, lambda0_omega_r };     // V_imr | lambda0 Omega_mr R_mr

  int lateral_flap_speed_sign = -1;                                          // s_b in a14_18, b14_3
  bool collective_trim_offset = true;                                        // delta_col0 in dA1/dmu
  FlapInflowSignSource flap_inflow_sign_source = FlapInflowSignSource::u_a;  // s_mu in K_z
  int fuselage_downwash_sign = -1;                                           // w_a +/- V_imr in Z_fus
  int tail_rotor_velocity_sign = -1;                                         // sign of Y_v^tr
  YawInertia yaw_inertia = YawInertia::minus_rotor;
  RotorSpeedModel rotor_speed_model = RotorSpeedModel::thrust_inversion;
  int horizontal_tail_sign = -1;                                             // sign of Z_ht
  Solidity solidity = Solidity::computed;
  TailRotorTorque tail_rotor_torque = TailRotorTorque::profile;
  InducedVelocityModel induced_velocity_model = InducedVelocityModel::constant;

  // The default: every §9 resolution.
  static ModelOptions resolved() { return {}; }
  // The paper-literal preset of §9: every switch that has a paper alternative at "paper".
  // (A-10's implicit paper form is identical to minus_rotor; have no paper
  // alternative and keep the resolved value.)
  static ModelOptions paper();
  // "resolved" or "paper"; throws thetad::Error otherwise.
  static ModelOptions preset(std::string_view name);

  // The switch names, exactly as in docs/model.md §11 (the keys of the settings files).
  static constexpr std::array<std::string_view, 11> names = {
      "lateral_flap_speed_sign", "collective_trim_offset", "flap_inflow_sign_source",
      "fuselage_downwash_sign",  "tail_rotor_velocity_sign", "yaw_inertia",
      "rotor_speed_model",       "horizontal_tail_sign",   "solidity",
      "tail_rotor_torque",       "induced_velocity_model"};

  // Sets one switch from its settings-file spelling: signs "+1"/"-1" (also "1"), on/off switches
  // "on"/"off", enums by their value name (e.g. "lambda0_omega_r"). Throws thetad::Error naming
  // the switch and the accepted values when the name or the value is unknown.
  void set(std::string_view name, std::string_view value);
  // The value of one switch in the same spelling that set() accepts.
  std::string get(std::string_view name) const;
  // "name=value" for every switch, comma separated, in the order of `names`.
  std::string to_string() const;

  bool operator==(const ModelOptions&) const = default;
};

}  // namespace thetad::heli
