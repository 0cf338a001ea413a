#pragma once

// The X-Cell helicopter's SDC form F(x), B(x) (docs/model.md §6) for an exported controller's step:
// standard C++ only, templated on the scalar type, no heap, no exceptions. A second implementation
// of core/helicopter (forces.cpp, helicopter.cpp, rotor_speed.cpp) for the controller's model (no
// wind, nominal induced velocities); tests/export/onboard_helicopter_test.cpp holds it to the
// library's F and B. `thetad export` copies this file into the header it writes.

#ifndef THETAD_ONBOARD_HELICOPTER_SDC
#define THETAD_ONBOARD_HELICOPTER_SDC

#include <cmath>
#include <limits>

namespace thetad_onboard {

inline constexpr int kStates = 18;
inline constexpr int kInputs = 5;

// What a step reports instead of throwing: the library's thetad::Error cases, by cause.
enum class Status : int {
  ok = 0,
  pitch_beyond_limit,        // |theta| > 85 deg or not finite (docs/model.md §3.4)
  invalid_thrust,            // T_mr negative or not finite, or the airspeed not finite
  no_rotor_speed,            // A4 has no root in the rotor-speed bracket (docs/model.md §4.2)
  rotor_speed_not_converged, // the root finder hit its iteration cap
  bias_state_zero,           // s = 0 or not finite: F's column 18 divides by s
  not_finite,                // the computed input is NaN or infinite
  schur_not_converged,       // the SDRE's real Schur form hit its QR sweep cap
  closed_loop_not_hurwitz,   // the SDRE's Newton–Kleinman iterate does not stabilize (F, B) here
  lyapunov_singular,         // the SDRE's Lyapunov operator is singular to working precision
};

inline const char* status_name(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::pitch_beyond_limit: return "pitch beyond +/-85 deg";
    case Status::invalid_thrust: return "thrust or airspeed not finite and non-negative";
    case Status::no_rotor_speed: return "no main-rotor speed for the thrust";
    case Status::rotor_speed_not_converged: return "main-rotor speed iteration did not converge";
    case Status::bias_state_zero: return "bias state s is zero or not finite";
    case Status::not_finite: return "input not finite";
    case Status::schur_not_converged: return "real Schur form did not converge";
    case Status::closed_loop_not_hurwitz: return "Newton-Kleinman closed loop not Hurwitz";
    case Status::lyapunov_singular: return "Lyapunov operator singular";
  }
  return "unknown";
}

// Indices of docs/model.md §2 (core/helicopter/state.hpp).
enum : int { kXp = 0, kYp, kZp, kU, kV, kW, kPhi, kTheta, kPsi, kP, kQ, kR, kA1, kB1, kXi, kYi, kZi, kS };
enum : int { kTmr = 0, kPed, kCol, kLon, kLat };

// The rows where B can be nonzero (helicopter.cpp's fill_*_sdc): a value function's gradient is
// needed there only.
inline constexpr int kInputRowCount = 8;
inline constexpr int kInputRows[kInputRowCount] = {kU, kV, kW, kP, kQ, kR, kA1, kB1};

// The model's parameters and switches (docs/model.md §5, §11) with the derived quantities in effect,
// as the generator wrote them (export/helicopter_constants.cpp fills it from a heli::Helicopter).
struct HelicopterConstants {
  double mass, gravity, ixx, iyy, izz, yaw_inertia;
  double k_beta, k_mu, tau_e, a_lon_nom, b_lat_nom, lift_slope_mr;
  double radius_mr, radius_tr, cd0_mr, cd0_tr, lambda0, eta_w, omega_nom, gear_tr;
  double h_mr, h_tr, l_tr, l_ht;
  double cd_x, cd_y, cd_z, s_fus_x, s_fus_y, s_fus_z, s_ht, s_vf, cla_ht, cla_vf, eps_vf_tr;
  double v_imr, v_itr, y_ped_tr, y_v_tr, rho, k_s;
  double solidity, tail_rotor_solidity, trim_collective, wake_skew_start, wake_skew_end;
  // Switches: signs are +1 or -1; the others 1 (on) or 0.
  double lateral_flap_speed_sign, fuselage_downwash_sign, tail_rotor_velocity_sign, horizontal_tail_sign;
  int flap_inflow_sign_from_u_a, rotor_speed_governor, tail_rotor_profile_torque, induced_velocity_lambda0;
  double min_rotor_speed, max_rotor_speed, max_pitch;  // rad/s, rad/s, rad
};

// The root finder's relative tolerance: the library's 1e-12 in double, a few units in the last
// place in float (below that the residual's rounding decides the steps).
template <class T>
constexpr T rotor_speed_tolerance() {
  return std::numeric_limits<T>::digits > 30 ? T(1e-12) : T(16) * std::numeric_limits<T>::epsilon();
}
// Safeguarded Newton halves the bracket [20, 600] rad/s at least every other step: 100 steps are
// far beyond what either tolerance needs.
inline constexpr int kRotorSpeedIterations = 100;

namespace detail {

// A4 as g(Omega) = k Omega sqrt(V_h^2 + (c Omega - w_a)^2) - T (rotor_speed.cpp's ThrustResidual).
template <class T>
struct ThrustResidual {
  T k, c, vh2, w_a, thrust;
  T value(T omega) const {
    const T y = c * omega - w_a;
    return k * omega * std::sqrt(vh2 + y * y) - thrust;
  }
  void with_derivative(T omega, T& value, T& derivative) const {
    const T y = c * omega - w_a;
    const T norm = std::sqrt(vh2 + y * y);
    value = k * omega * norm - thrust;
    derivative = k * (vh2 + y * y + omega * c * y) / norm;
  }
};

template <class T>
Status root_in_monotonic_interval(const ThrustResidual<T>& g, T lo, T hi, T g_lo, T start, T& root) {
  const T tolerance = rotor_speed_tolerance<T>();
  T omega = start;
  for (int iteration = 0; iteration < kRotorSpeedIterations; ++iteration) {
    T value, derivative;
    g.with_derivative(omega, value, derivative);
    if (value == T(0)) {
      root = omega;
      return Status::ok;
    }
    if ((value < T(0)) == (g_lo < T(0))) {
      lo = omega;
      g_lo = value;
    } else {
      hi = omega;
    }
    T next = omega - value / derivative;
    if (!(next > lo && next < hi)) next = T(0.5) * (lo + hi);  // also a NaN step at the kink
    const bool converged = std::abs(next - omega) <= tolerance * next || hi - lo <= tolerance * lo;
    omega = next;
    if (converged) {
      root = omega;
      return Status::ok;
    }
  }
  return Status::rotor_speed_not_converged;
}

// Omega_mr for thrust T_mr (rotor_speed.cpp's main_rotor_speed): the root of A4 nearest `hint` over
// the intervals where A4 is monotonic.
template <class T>
Status main_rotor_speed(const HelicopterConstants& p, T thrust, T horizontal_airspeed, T w_a, T hint, T& speed) {
  if (!std::isfinite(thrust) || thrust < T(0) || !std::isfinite(horizontal_airspeed) || !std::isfinite(w_a))
    return Status::invalid_thrust;
  const T r = T(p.radius_mr), pi = T(3.141592653589793238462643383279502884);
  const ThrustResidual<T> g{T(2.0) * T(p.eta_w) * T(p.lambda0) * T(p.rho) * pi * r * r * r, T(p.lambda0) * r,
                            horizontal_airspeed * horizontal_airspeed, w_a, thrust};
  const T min_speed = T(p.min_rotor_speed), max_speed = T(p.max_rotor_speed);
  T breaks[4] = {min_speed, max_speed, max_speed, max_speed};
  int count = 2;
  const T discriminant = w_a * w_a - T(8.0) * g.vh2;
  if (w_a > T(0) && discriminant > T(0)) {
    const T root = std::sqrt(discriminant);
    const T criticals[2] = {(T(3.0) * w_a - root) / (T(4.0) * g.c), (T(3.0) * w_a + root) / (T(4.0) * g.c)};
    for (const T critical : criticals) {
      if (critical > breaks[count - 2] && critical < max_speed) {
        breaks[count - 1] = critical;
        breaks[count++] = max_speed;
      }
    }
  }
  bool found = false;
  T best = T(0);
  for (int i = 0; i + 1 < count; ++i) {
    const T lo = breaks[i], hi = breaks[i + 1];
    const T g_lo = g.value(lo), g_hi = g.value(hi);
    if ((g_lo > T(0) && g_hi > T(0)) || (g_lo < T(0) && g_hi < T(0))) continue;
    const T start = hint < lo ? lo : hint > hi ? hi : hint;
    T omega = lo;
    if (g_lo != T(0)) {
      omega = hi;
      if (g_hi != T(0)) {
        const Status status = root_in_monotonic_interval(g, lo, hi, g_lo, start, omega);
        if (status != Status::ok) return status;
      }
    }
    if (!found || std::abs(omega - hint) < std::abs(best - hint)) best = omega;
    found = true;
  }
  if (!found) return Status::no_rotor_speed;
  speed = best;
  return Status::ok;
}

template <class T>
T clamp_magnitude(T value, T limit) {
  return std::abs(value) <= limit ? value : value < T(0) ? -limit : limit;
}

template <class T>
T planar_norm(T a, T b) {
  const T squared = a * a + b * b;
  return squared == T(0) ? T(0) : std::sqrt(squared);
}

template <class T>
T sinc(T x, T sin_x) {
  return std::abs(x) < T(1e-4) ? T(1.0) - x * x / T(6.0) : sin_x / x;
}

}  // namespace detail

// Attitude and air data at x (forces.cpp's air_data, still air): the Euler trigonometry, R(Theta)
// row-major and the air-relative velocity.
template <class T>
struct AirData {
  T sin_phi, cos_phi, sin_theta, cos_theta, tan_theta, sec_theta;
  T rotation[9];
  T u_a, v_a, w_a;
};

template <class T>
Status air_data(const HelicopterConstants& p, const T* x, AirData<T>& a) {
  const T phi = x[kPhi], theta = x[kTheta], psi = x[kPsi];
  if (!(std::abs(theta) <= T(p.max_pitch))) return Status::pitch_beyond_limit;
  a.sin_phi = std::sin(phi);
  a.cos_phi = std::cos(phi);
  a.sin_theta = std::sin(theta);
  a.cos_theta = std::cos(theta);
  a.tan_theta = a.sin_theta / a.cos_theta;
  a.sec_theta = T(1.0) / a.cos_theta;
  const T sin_psi = std::sin(psi), cos_psi = std::cos(psi);
  // Eq. (2), body -> NED.
  a.rotation[0] = a.cos_theta * cos_psi;
  a.rotation[1] = a.sin_phi * a.sin_theta * cos_psi - a.cos_phi * sin_psi;
  a.rotation[2] = a.cos_phi * a.sin_theta * cos_psi + a.sin_phi * sin_psi;
  a.rotation[3] = a.cos_theta * sin_psi;
  a.rotation[4] = a.sin_phi * a.sin_theta * sin_psi + a.cos_phi * cos_psi;
  a.rotation[5] = a.cos_phi * a.sin_theta * sin_psi - a.sin_phi * cos_psi;
  a.rotation[6] = -a.sin_theta;
  a.rotation[7] = a.sin_phi * a.cos_theta;
  a.rotation[8] = a.cos_phi * a.cos_theta;
  a.u_a = x[kU];
  a.v_a = x[kV];
  a.w_a = x[kW];
  return Status::ok;
}

// F (18 x 18) and B (18 x 5), row-major, every entry written, of Eqs. (29)-(30) at x with the rotor
// speed that the thrust T_mr gives (docs/model.md §6.2), or Omega_nom with the governor model.
template <class T>
Status helicopter_sdc(const HelicopterConstants& p, const T* x, T thrust, T* F, T* B) {
  AirData<T> a;
  Status status = air_data(p, x, a);
  if (status != Status::ok) return status;
  const T s = x[kS];
  if (s == T(0) || !std::isfinite(s)) return Status::bias_state_zero;
  T omega = T(p.omega_nom);
  if (p.rotor_speed_governor) {
    if (!std::isfinite(thrust)) return Status::invalid_thrust;
  } else {
    status = detail::main_rotor_speed(p, thrust, T(std::sqrt(a.u_a * a.u_a + a.v_a * a.v_a)), a.w_a,
                                      T(p.omega_nom), omega);
    if (status != Status::ok) return status;
  }
  const T pi = T(3.141592653589793238462643383279502884);
  const T rho = T(p.rho), m = T(p.mass), g = T(p.gravity), ixx = T(p.ixx), iyy = T(p.iyy), izz = T(p.izz);
  const T izz_eff = T(p.yaw_inertia), r_mr = T(p.radius_mr);
  const T u_a = a.u_a, v_a = a.v_a, w_a = a.w_a;
  const T pr = x[kP], qr = x[kQ], rr = x[kR];

  // Rotor inflow and induced velocities (forces.cpp's forces_of).
  const T tip_speed = omega * r_mr;
  const T mu = detail::planar_norm(u_a, v_a) / tip_speed;  // A5
  const T mu_z = w_a / tip_speed;                          // A6
  const T induced_main = p.induced_velocity_lambda0 ? T(T(p.lambda0) * tip_speed) : T(p.v_imr);
  const T induced_tail = T(p.v_itr);
  T wake_factor = T(0);  // A1-A3
  if (!(induced_main <= w_a)) {
    const T chi = u_a / (induced_main - w_a);
    const T start = T(p.wake_skew_start), end = T(p.wake_skew_end);
    wake_factor = chi <= start ? T(0) : chi >= end ? T(1.5) : T(1.5) * (chi - start) / (end - start);
  }
  // Fuselage, A7-A9.
  const T w_fus = w_a + T(p.fuselage_downwash_sign) * induced_main;
  const T v_inf = std::sqrt(u_a * u_a + v_a * v_a + w_fus * w_fus);
  const T x_fus = T(-0.5) * rho * T(p.cd_x) * T(p.s_fus_x) * u_a * v_inf;
  const T y_fus = T(-0.5) * rho * T(p.cd_y) * T(p.s_fus_y) * v_a * v_inf;
  const T z_fus = T(-0.5) * rho * T(p.cd_z) * T(p.s_fus_z) * w_fus * v_inf;
  // Tail rotor, vertical fin, horizontal tail (forces.cpp's fill_tail_forces).
  const T l_tr = T(p.l_tr), h_tr = T(p.h_tr), l_ht = T(p.l_ht);
  const T v_tr = v_a - l_tr * rr + h_tr * pr;
  const T y_tr = T(p.tail_rotor_velocity_sign) * m * T(std::abs(p.y_v_tr)) * v_tr;
  const T l_tr_moment = h_tr * y_tr, n_tr = -l_tr * y_tr;
  const T w_tr = w_a + l_tr * qr - wake_factor * induced_main;
  const T v_inf_tr_sq = u_a * u_a + w_tr * w_tr;
  const T v_vf = v_a - T(p.eps_vf_tr) * induced_tail - l_tr * rr;
  const T y_vf_free = T(-0.5) * rho * T(p.s_vf) * (T(p.cla_vf) * detail::planar_norm(u_a, w_tr) + std::abs(v_vf)) * v_vf;
  const T y_vf = detail::clamp_magnitude(y_vf_free, T(T(0.5) * rho * T(p.s_vf) * (v_inf_tr_sq + v_vf * v_vf)));
  const T l_vf = h_tr * y_vf, n_vf = -l_tr * y_vf;
  const T w_ht = w_a + l_ht * qr - wake_factor * induced_main;
  const T z_ht_free = T(p.horizontal_tail_sign) * T(0.5) * rho * T(p.s_ht) *
                      (T(p.cla_ht) * std::abs(u_a) * w_ht + std::abs(w_ht) * w_ht);
  const T z_ht = detail::clamp_magnitude(z_ht_free, T(T(0.5) * rho * T(p.s_ht) * (u_a * u_a + w_ht * w_ht)));
  const T m_ht = l_ht * z_ht;
  // Rotor torques (fill_rotor_torques).
  const T sigma = T(p.solidity);
  const T inflow = T(p.lambda0) - mu_z;
  const T thrust_coefficient = T(2.0) * T(p.eta_w) * T(p.lambda0) * std::sqrt(mu * mu + inflow * inflow);
  const T torque_coefficient =
      thrust_coefficient * inflow + T(p.cd0_mr) * sigma / T(8.0) * (T(1.0) + T(7.0) / T(3.0) * mu * mu);
  const T q_mr = torque_coefficient * rho * tip_speed * tip_speed * pi * r_mr * r_mr * r_mr;
  T q_tr = T(0);
  if (p.tail_rotor_profile_torque) {
    const T omega_tr = T(p.gear_tr) * omega;
    const T r_tr = T(p.radius_tr);
    q_tr = rho * pi * (r_tr * r_tr * r_tr * r_tr * r_tr) * omega_tr * omega_tr * T(p.cd0_tr) *
           T(p.tail_rotor_solidity) / T(8.0);
  }
  // Flapping, §2.5 resolved form (fill_flapping_derivatives).
  const T flap_scale = T(1.0) / (T(p.tau_e) * tip_speed);
  const T sign_mu = p.flap_inflow_sign_from_u_a && u_a < T(0) ? T(-1.0) : T(1.0);
  const T k_z = T(16.0) * T(p.k_mu) * mu * mu * sign_mu / (T(8.0) * mu + T(p.lift_slope_mr) * sigma);
  const T c_col0 = T(2.0) * T(p.k_mu) * (T(4.0) * T(p.trim_collective) / T(3.0) - T(p.lambda0));
  const T c_col_per_input = T(8.0) * T(p.k_mu) / T(3.0);
  const T s_b = T(p.lateral_flap_speed_sign);
  const T a1_speed = (k_z * w_a + c_col0 * u_a) * flap_scale;
  const T b1_speed = s_b * c_col0 * v_a * flap_scale;
  const T a1_per_collective = c_col_per_input * u_a * flap_scale;
  const T b1_per_collective = s_b * c_col_per_input * v_a * flap_scale;
  const T speed_ratio = omega / T(p.omega_nom);
  const T a1_per_lon = T(p.a_lon_nom) / T(p.tau_e) * speed_ratio * speed_ratio;
  const T b1_per_lat = T(p.b_lat_nom) / T(p.tau_e) * speed_ratio * speed_ratio;

  for (int i = 0; i < kStates * kStates; ++i) F[i] = T(0);
  for (int i = 0; i < kStates * kInputs; ++i) B[i] = T(0);
  auto f = [F](int row, int col) -> T& { return F[row * kStates + col]; };
  auto b = [B](int row, int col) -> T& { return B[row * kInputs + col]; };
  // The entries that no state changes (helicopter.cpp's fill_constant_sdc).
  f(kPhi, kP) = T(1.0);
  f(kP, kB1) = T(p.k_beta) / ixx;
  f(kQ, kA1) = T(p.k_beta) / iyy;
  f(kA1, kQ) = T(-1.0);
  f(kA1, kA1) = T(-1.0) / T(p.tau_e);
  f(kB1, kP) = T(-1.0);
  f(kB1, kB1) = T(-1.0) / T(p.tau_e);
  f(kXi, kXp) = T(1.0);  // Eq. (9)
  f(kYi, kYp) = T(1.0);
  f(kZi, kZp) = T(1.0);
  f(kS, kS) = -T(p.k_s);  // Eq. (26)
  const T y_ped = T(p.y_ped_tr);
  b(kV, kPed) = y_ped;
  b(kW, kTmr) = T(-1.0) / m;
  b(kP, kPed) = h_tr * m * y_ped / ixx;
  b(kR, kPed) = -m * y_ped * l_tr / izz_eff;
  // The rest (fill_varying_sdc). Rows 1-3: Eq. (1).
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) f(kXp + r, kU + c) = a.rotation[r * 3 + c];
  // Rows 4-6: omega-tilde, gravity by sinc, biases in column 18.
  f(kU, kV) = rr;
  f(kU, kW) = -qr;
  f(kV, kU) = -rr;
  f(kV, kW) = pr;
  f(kW, kU) = qr;
  f(kW, kV) = -pr;
  f(kU, kTheta) = -g * detail::sinc(x[kTheta], a.sin_theta);
  f(kV, kPhi) = g * a.cos_theta * detail::sinc(x[kPhi], a.sin_phi);
  f(kU, kS) = x_fus / (m * s);
  f(kV, kS) = (y_fus + y_tr + y_vf) / (m * s);
  f(kW, kS) = z_fus / (m * s) + g * a.cos_phi * a.cos_theta / s;
  // Rows 7-9: Eq. (5).
  f(kPhi, kQ) = a.sin_phi * a.tan_theta;
  f(kPhi, kR) = a.cos_phi * a.tan_theta;
  f(kTheta, kQ) = a.cos_phi;
  f(kTheta, kR) = -a.sin_phi;
  f(kPsi, kQ) = a.sin_phi * a.sec_theta;
  f(kPsi, kR) = a.cos_phi * a.sec_theta;
  // Rows 10-12: Eq. (4), row 12 in the explicit form of A-10.
  f(kP, kQ) = rr * iyy / ixx;
  f(kP, kR) = -qr * izz / ixx;
  f(kP, kS) = (l_vf + l_tr_moment) / (ixx * s);
  f(kQ, kP) = -rr * ixx / iyy;
  f(kQ, kR) = pr * izz / iyy;
  f(kQ, kS) = m_ht / (iyy * s);
  f(kR, kP) = qr * ixx / izz_eff;
  f(kR, kQ) = -pr * iyy / izz_eff;
  f(kR, kS) = (n_vf + n_tr - q_mr - T(p.gear_tr) * q_tr) / (izz_eff * s);
  // Rows 13-14: Eq. (6), resolved form of §2.5.
  f(kA1, kS) = a1_speed / s;
  f(kB1, kS) = b1_speed / s;
  const T a1 = x[kA1], b1 = x[kB1];
  b(kU, kTmr) = -a1 / m;
  b(kV, kTmr) = b1 / m;
  b(kP, kTmr) = T(p.h_mr) * b1 / ixx;
  b(kQ, kTmr) = T(p.h_mr) * a1 / iyy;
  b(kA1, kCol) = a1_per_collective;
  b(kA1, kLon) = a1_per_lon;
  b(kB1, kCol) = b1_per_collective;
  b(kB1, kLat) = b1_per_lat;
  return Status::ok;
}

}  // namespace thetad_onboard

#endif  // THETAD_ONBOARD_HELICOPTER_SDC
