#include "core/helicopter/helicopter.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/helicopter/equations_of_motion.hpp"
#include "core/helicopter/forces.hpp"
#include "core/helicopter/paper_weights.hpp"
#include "core/helicopter/rotor_speed.hpp"

namespace thetad::heli {

namespace {

[[noreturn]] void throw_size_error(const char* what, Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                                   Eigen::Index want_cols) {
  std::ostringstream message;
  message << "helicopter: " << what << " is " << rows << "x" << cols << ", expected " << want_rows << "x" << want_cols;
  throw Error(message.str());
}

// Inline, so that the hot path pays two comparisons and no call.
inline void require_size(const char* what, Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                         Eigen::Index want_cols) {
  if (rows != want_rows || cols != want_cols) [[unlikely]]
    throw_size_error(what, rows, cols, want_rows, want_cols);
}

// sin(x)/x from sin_x = sin(x), which the air data already holds; exact to double precision near
// 0 by its Taylor series (docs/model.md §6.1).
double sinc(double x, double sin_x) { return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : sin_x / x; }

// Omega_mr for the applied thrust at the air data of the state (A4, or the governor of A-11).
double rotor_speed_at(const Parameters& p, const ModelOptions& options, const AirData& air, double thrust) {
  if (options.rotor_speed_model == ModelOptions::RotorSpeedModel::governor) {
    if (!std::isfinite(thrust)) throw Error("helicopter: main-rotor thrust T_mr = " + std::to_string(thrust) + " N is not finite");
    return p.omega_nom;
  }
  return main_rotor_speed(p, thrust, std::sqrt(air.u_a * air.u_a + air.v_a * air.v_a), air.w_a, p.omega_nom);
}

// The entries of Eqs. (29)-(30) that no state, input or rotor speed changes (docs/model.md §6.1),
// zeros included: written once into a controller's buffers, then left alone by fill_varying_sdc.
void fill_constant_sdc(const Parameters& p, double yaw_inertia, Eigen::Ref<Eigen::MatrixXd> F,
                       Eigen::Ref<Eigen::MatrixXd> B) {
  const double m = p.mass, ixx = p.ixx, iyy = p.iyy;
  F.setZero();
  B.setZero();
  F(kPhi, kP) = 1.0;
  F(kP, kB1) = p.k_beta / ixx;
  F(kQ, kA1) = p.k_beta / iyy;
  F(kA1, kQ) = -1.0;
  F(kA1, kA1) = -1.0 / p.tau_e;
  F(kB1, kP) = -1.0;
  F(kB1, kB1) = -1.0 / p.tau_e;
  F(kXi, kXp) = 1.0;  // rows 15-17: Eq. (9)
  F(kYi, kYp) = 1.0;
  F(kZi, kZp) = 1.0;
  F(kS, kS) = -p.k_s;  // row 18: Eq. (26)
  B(kV, kPed) = p.y_ped_tr;
  B(kW, kTmr) = -1.0 / m;
  B(kP, kPed) = p.h_tr * m * p.y_ped_tr / ixx;
  B(kR, kPed) = -m * p.y_ped_tr * p.l_tr / yaw_inertia;
}

// Every other entry of Eqs. (29)-(30), from the shared forces.
void fill_varying_sdc(const Parameters& p, const Forces& f, const Eigen::Ref<const Eigen::VectorXd>& x,
                      Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) {
  const AirData& a = f.air;
  const double s = x[kS];
  if (s == 0.0 || !std::isfinite(s)) {
    throw Error("helicopter: bias state s = " + std::to_string(s) + " cannot carry the bias terms (col. 18 divides by s)");
  }
  const double m = p.mass, g = p.gravity, ixx = p.ixx, iyy = p.iyy, izz_eff = f.yaw_inertia;
  const double pr = x[kP], qr = x[kQ], rr = x[kR];

  F.block<3, 3>(kXp, kU) = a.rotation;  // rows 1-3: Eq. (1)
  // Rows 4-6: omega-tilde (Eq. 3's -omega x V), gravity by sinc, biases in column 18.
  F(kU, kV) = rr;
  F(kU, kW) = -qr;
  F(kV, kU) = -rr;
  F(kV, kW) = pr;
  F(kW, kU) = qr;
  F(kW, kV) = -pr;
  F(kU, kTheta) = -g * sinc(x[kTheta], a.sin_theta);           // a4_8
  F(kV, kPhi) = g * a.cos_theta * sinc(x[kPhi], a.sin_phi);   // a5_7
  F(kU, kS) = f.x_fus / (m * s);                                      // a4_18
  F(kV, kS) = (f.y_fus + f.y_tr + f.y_vf) / (m * s);                  // a5_18
  F(kW, kS) = f.z_fus / (m * s) + g * a.cos_phi * a.cos_theta / s;    // a6_18
  // Rows 7-9: Eq. (5).
  F(kPhi, kQ) = a.sin_phi * a.tan_theta;
  F(kPhi, kR) = a.cos_phi * a.tan_theta;
  F(kTheta, kQ) = a.cos_phi;
  F(kTheta, kR) = -a.sin_phi;
  F(kPsi, kQ) = a.sin_phi * a.sec_theta;
  F(kPsi, kR) = a.cos_phi * a.sec_theta;
  // Rows 10-12: Eq. (4), row 12 in the explicit form of A-10.
  F(kP, kQ) = rr * iyy / ixx;
  F(kP, kR) = -qr * p.izz / ixx;
  F(kP, kS) = (f.l_vf + f.l_tr) / (ixx * s);
  F(kQ, kP) = -rr * ixx / iyy;
  F(kQ, kR) = pr * p.izz / iyy;
  F(kQ, kS) = f.m_ht / (iyy * s);
  F(kR, kP) = qr * ixx / izz_eff;
  F(kR, kQ) = -pr * iyy / izz_eff;
  F(kR, kS) = (f.n_vf + f.n_tr - f.q_mr - p.gear_tr * f.q_tr) / (izz_eff * s);
  // Rows 13-14: Eq. (6), resolved form of §2.5.
  F(kA1, kS) = f.a1_speed / s;
  F(kB1, kS) = f.b1_speed / s;

  const double a1 = x[kA1], b1 = x[kB1];
  B(kU, kTmr) = -a1 / m;
  B(kV, kTmr) = b1 / m;  // b1/m, not the printed a1/m
  B(kP, kTmr) = p.h_mr * b1 / ixx;
  B(kQ, kTmr) = p.h_mr * a1 / iyy;
  B(kA1, kCol) = f.a1_per_collective;
  B(kA1, kLon) = f.a1_per_lon;
  B(kB1, kCol) = f.b1_per_collective;
  B(kB1, kLat) = f.b1_per_lat;
}

}  // namespace

Helicopter::Helicopter(const Parameters& parameters, const ModelOptions& options)
    : parameters_(parameters), options_(options) {}

DesignDefaults Helicopter::design_defaults() const {
  Eigen::VectorXd hover_thrust = Eigen::VectorXd::Zero(kInputDim);
  hover_thrust(kTmr) = parameters_.mass * parameters_.gravity;
  return {paper_state_weights(), paper_input_weights(), hover_thrust};
}

double Helicopter::rotor_speed(const Eigen::Ref<const Eigen::VectorXd>& x, double thrust) const {
  require_size("state", x.rows(), x.cols(), kStateDim, 1);
  return rotor_speed_at(parameters_, options_, air_data(environment_, x), thrust);
}

void Helicopter::f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                   Eigen::Ref<Eigen::VectorXd> xdot) const {
  require_size("state", x.rows(), x.cols(), kStateDim, 1);
  require_size("input", u.rows(), u.cols(), kInputDim, 1);
  require_size("state derivative", xdot.rows(), xdot.cols(), kStateDim, 1);
  const AirData air = air_data(environment_, x);
  const Forces forces = evaluate_forces(parameters_, options_, environment_, air, x,
                                        rotor_speed_at(parameters_, options_, air, u[kTmr]));
  equations_of_motion(parameters_, forces, x, u, xdot);
}

bool Helicopter::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                          Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const {
  require_size("input", u.rows(), u.cols(), kInputDim, 1);
  require_size("df/dx", dfdx.rows(), dfdx.cols(), kStateDim, kStateDim);
  require_size("df/du", dfdu.rows(), dfdu.cols(), kStateDim, kInputDim);
  const double omega = rotor_speed(x, u[kTmr]);  // checks x
  constexpr int directions = kStateDim + kInputDim;
  DualState xd;
  DualInput ud;
  for (int i = 0; i < kStateDim; ++i) xd[i] = Dual(x[i], directions, i);
  for (int j = 0; j < kInputDim; ++j) ud[j] = Dual(u[j], directions, kStateDim + j);
  const BasicAirData<Dual> air = dual_air_data(environment_, xd);
  const Dual rotor = options_.rotor_speed_model == ModelOptions::RotorSpeedModel::governor
                         ? Dual(omega)
                         : implicit_rotor_speed(parameters_, omega, ud[kTmr], air.u_a * air.u_a + air.v_a * air.v_a, air.w_a);
  DualState xdot;
  equations_of_motion(parameters_, dual_forces(parameters_, options_, environment_, air, xd, rotor), xd, ud, xdot);
  for (int i = 0; i < kStateDim; ++i) {
    dfdx.row(i) = xdot[i].derivatives().head<kStateDim>().transpose();
    dfdu.row(i) = xdot[i].derivatives().tail<kInputDim>().transpose();
  }
  return true;
}

void Helicopter::sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                     Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  sdc_constant(F, B);
  sdc_varying(x, u, F, B);
}

void Helicopter::sdc_constant(Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  require_size("F", F.rows(), F.cols(), kStateDim, kStateDim);
  require_size("B", B.rows(), B.cols(), kStateDim, kInputDim);
  fill_constant_sdc(parameters_, parameters_.effective_yaw_inertia(options_.yaw_inertia), F, B);
}

void Helicopter::sdc_varying(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                             Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  require_size("state", x.rows(), x.cols(), kStateDim, 1);
  require_size("input", u.rows(), u.cols(), kInputDim, 1);
  require_size("F", F.rows(), F.cols(), kStateDim, kStateDim);
  require_size("B", B.rows(), B.cols(), kStateDim, kInputDim);
  const AirData air = air_data(environment_, x);
  const double omega = rotor_speed_at(parameters_, options_, air, u[kTmr]);
  fill_varying_sdc(parameters_, evaluate_forces(parameters_, options_, environment_, air, x, omega), x, F, B);
}

void Helicopter::sdc_at_rotor_speed(const Eigen::Ref<const Eigen::VectorXd>& x, double rotor_speed,
                                    Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  require_size("state", x.rows(), x.cols(), kStateDim, 1);
  require_size("F", F.rows(), F.cols(), kStateDim, kStateDim);
  require_size("B", B.rows(), B.cols(), kStateDim, kInputDim);
  const AirData air = air_data(environment_, x);
  fill_constant_sdc(parameters_, parameters_.effective_yaw_inertia(options_.yaw_inertia), F, B);
  fill_varying_sdc(parameters_, evaluate_forces(parameters_, options_, environment_, air, x, rotor_speed), x, F, B);
}

}  // namespace thetad::heli
