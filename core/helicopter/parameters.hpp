#pragma once

#include "core/helicopter/model_options.hpp"

namespace thetad::heli {

// The physical parameters of the X-Cell 60 model (docs/model.md §5, the paper's Nomenclature), SI units.
// One field per quantity; the ones Table 1 perturbs are plain fields so that the uncertainty
// table can point at them. Derived quantities are member functions, so they follow perturbed
// inputs (docs/model.md §9.1: sigma from c_mr and R_mr, T_max from R_mr, rho, Omega_nom).
struct Parameters {
  double mass;              // m (kg)
  double gravity;           // g (m/s^2)
  double ixx;               // I_xx rolling moment of inertia (kg m^2)
  double iyy;               // I_yy pitching moment of inertia (kg m^2)
  double izz;               // I_zz yawing moment of inertia (kg m^2)
  double i_beta;            // I_beta^mr blade flapping inertia (kg m^2), used only through I_rot
  double k_beta;            // K_beta hub torsional stiffness (N m/rad)
  double k_mu;              // K_mu scaling of flap response to speed (-)
  double tau_e;             // tau_e flapping time constant (s)
  double a_lon_nom;         // A^nom_dlon longitudinal cyclic-to-flap gain (rad/rad)
  double b_lat_nom;         // B^nom_dlat lateral cyclic-to-flap gain (rad/rad)
  double lift_slope_mr;     // a = a_mr main-rotor blade lift-curve slope (1/rad)
  double lift_slope_tr;     // a_tr tail-rotor blade lift-curve slope (1/rad); unused by the equations
  double chord_mr;          // c_mr (m)
  double chord_tr;          // c_tr (m); only in the proposed Q_tr
  double radius_mr;         // R_mr (m)
  double radius_tr;         // R_tr (m)
  double cd0_mr;            // C_D0^mr blade zero-lift drag (-)
  double cd0_tr;            // C_D0^tr (-); only in the proposed Q_tr
  double ct_max_mr;         // C_Tmax^mr (-); only in T_max
  double solidity_nomenclature;  // sigma as printed in the Nomenclature
  double lambda0;           // lambda_0 constant main-rotor inflow ratio (-)
  double eta_w;             // eta_w non-ideal wake contraction (-)
  double omega_nom;         // Omega_nom nominal main-rotor speed (rad/s)
  double gear_tr;           // n_tr tail-to-main rotor gear ratio (-)
  double h_mr;              // main-rotor hub height above c.g. (m)
  double h_tr;              // tail-rotor height above c.g. (m)
  double l_tr;              // tail-rotor location behind c.g. (m)
  double l_ht;              // horizontal stabilizer location behind c.g. (m)
  double cd_x, cd_y, cd_z;  // fuselage drag coefficients (-)
  double s_fus_x, s_fus_y, s_fus_z;  // fuselage drag areas (m^2)
  double s_ht;              // horizontal tail area (m^2)
  double s_vf;              // effective vertical fin area (m^2)
  double cla_ht;            // C_La^ht horizontal tail lift-curve slope (1/rad)
  double cla_vf;            // C_La^vf vertical fin lift-curve slope (1/rad)
  double eps_vf_tr;         // eps_vf^tr fin fraction in the tail-rotor wake (-)
  double v_imr;             // V_imr induced main-rotor velocity (m/s)
  double v_itr;             // V_itr induced tail-rotor velocity (m/s)
  double y_ped_tr;          // Y_dped^tr tail-rotor side acceleration per pedal (m/(s^2 rad))
  double y_v_tr;            // Y_v^tr tail-rotor side-force derivative (1/s), printed +0.06 (sign: A-9)
  double rho;               // air density (kg/m^3)
  double k_s;               // bias-state decay rate of Eq. 26 (1/s), proposed
  double collective_trim_offset;  // delta_col0 hover blade collective (rad), proposed

  // The values of docs/model.md §5.
  static Parameters nominal();

  // sigma: 0.0361 as printed, or 2 c_mr/(pi R_mr) for two blades.
  double solidity(ModelOptions::Solidity which) const;
  // I_rot = 2.5 I_beta^mr, "rotating inertia of the main rotor blade" (Nomenclature).
  double rotor_inertia() const;
  // The yaw inertia of the explicit r-equation: I_zz - I_rot, I_zz or I_zz + I_rot.
  double effective_yaw_inertia(ModelOptions::YawInertia which) const;
  // eta_i = (l_tr - R_mr - R_tr)/h_tr (A2) and eta_f = (l_tr - R_mr + R_tr)/h_tr (A3).
  double wake_skew_start() const;
  double wake_skew_end() const;
  // sigma_tr = 2 c_tr/(pi R_tr).
  double tail_rotor_solidity() const;
  // T_max = C_Tmax rho pi R_mr^2 (Omega_nom R_mr)^2 (docs/model.md §5, derived).
  double max_main_rotor_thrust() const;
  // delta_col0 in effect: the parameter when the A-6 switch is on, else 0.
  double trim_collective(const ModelOptions& options) const;
};

}  // namespace thetad::heli
