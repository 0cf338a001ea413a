#include "core/helicopter/forces.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "core/error.hpp"

namespace thetad::heli {

namespace {

constexpr double kMaxPitch = 85.0 * std::numbers::pi / 180.0;  // docs/model.md §3.4 guard

// A magnitude clamp that keeps the sign (stall limits, A-20).
template <class T>
T clamp_magnitude(const T& value, const T& limit) {
  using std::abs;
  return abs(value) <= limit ? value : value < 0.0 ? T(-limit) : limit;
}

// K_lambda, Eqs. A1-A3: the fraction of the main-rotor downwash that reaches the tail surfaces.
template <class T>
T wake_factor(const Parameters& p, const T& u_a, const T& w_a, const T& induced_main) {
  if (induced_main <= w_a) return 0.0;  // tested first: chi's denominator is then positive
  const T chi = u_a / (induced_main - w_a);
  const double start = p.wake_skew_start(), end = p.wake_skew_end();
  if (chi <= start) return 0.0;
  if (chi >= end) return 1.5;
  return 1.5 * (chi - start) / (end - start);
}

// sqrt(a^2 + b^2), with slope 0 at the origin where it has none (in hover, with the air still in
// the rotor plane and at the tail): there the advance ratio mu enters the equations as mu^2 and
// mu^2/(8 mu + a sigma), whose slope is 0, and the fin's airspeed as a kink, like abs() elsewhere.
template <class T>
T planar_norm(const T& a, const T& b) {
  using std::sqrt;
  const T squared = a * a + b * b;
  return squared == 0.0 ? T(0.0) : T(sqrt(squared));
}

template <class T, class State>
BasicAirData<T> air_data_of(const Environment& environment, const State& x) {
  using std::abs, std::cos, std::sin;
  const T phi = x[kPhi], theta = x[kTheta], psi = x[kPsi];
  if (!(abs(value_of(theta)) <= kMaxPitch)) {
    std::ostringstream message;
    message << "helicopter: pitch angle theta = " << value_of(theta) << " rad ("
            << value_of(theta) * 180.0 / std::numbers::pi
            << " deg) is beyond +/-85 deg, where the Euler kinematics (Eq. 5) become singular";
    throw Error(message.str());
  }
  BasicAirData<T> a;
  a.sin_phi = sin(phi);
  a.cos_phi = cos(phi);
  a.sin_theta = sin(theta);
  a.cos_theta = cos(theta);
  a.tan_theta = a.sin_theta / a.cos_theta;
  a.sec_theta = 1.0 / a.cos_theta;
  const T sin_psi = sin(psi), cos_psi = cos(psi);
  // Eq. (2), 3-2-1 direction cosines, body -> NED.
  a.rotation << a.cos_theta * cos_psi, a.sin_phi * a.sin_theta * cos_psi - a.cos_phi * sin_psi,
      a.cos_phi * a.sin_theta * cos_psi + a.sin_phi * sin_psi,
      a.cos_theta * sin_psi, a.sin_phi * a.sin_theta * sin_psi + a.cos_phi * cos_psi,
      a.cos_phi * a.sin_theta * sin_psi - a.sin_phi * cos_psi,
      -a.sin_theta, a.sin_phi * a.cos_theta, a.cos_phi * a.cos_theta;
  // §2.7.1: inertial wind rotated into body axes, then Table 1 #26-28 per body component. In still
  // air (the controllers' model) the airspeed is the state's own velocity, the same numbers without
  // waiting for the trigonometry, so the rotor speed's iteration can run alongside it.
  if ((environment.wind_ned.array() == 0.0).all()) {
    a.u_a = x[kU];
    a.v_a = x[kV];
    a.w_a = x[kW];
    return a;
  }
  const Eigen::Matrix<T, 3, 1> wind_body = environment.wind_body_scale.template cast<T>().cwiseProduct(
      a.rotation.transpose() * environment.wind_ned.template cast<T>());
  a.u_a = x[kU] - wind_body.x();
  a.v_a = x[kV] - wind_body.y();
  a.w_a = x[kW] - wind_body.z();
  return a;
}

// Tail rotor, vertical fin and horizontal tail of `f`, from its air data, induced velocities and
// wake factor.
template <class T, class State>
void fill_tail_forces(const Parameters& p, const ModelOptions& options, const State& x, BasicForces<T>& f) {
  using std::abs;
  const double rho = p.rho, m = p.mass;
  const T u_a = f.air.u_a, v_a = f.air.v_a, w_a = f.air.w_a;
  const T p_rate = x[kP], q_rate = x[kQ], r_rate = x[kR];

  // Tail rotor, velocity part (§2.7.5; sign of Y_v^tr: A-9) and its moments (App. B).
  const T v_tr = v_a - p.l_tr * r_rate + p.h_tr * p_rate;
  f.y_tr = options.tail_rotor_velocity_sign * m * std::abs(p.y_v_tr) * v_tr;
  f.l_tr = p.h_tr * f.y_tr;
  f.n_tr = -p.l_tr * f.y_tr;

  // Vertical fin (§2.7.5) with its stall clamp.
  const T w_tr = w_a + p.l_tr * q_rate - f.wake_factor * f.induced_main;
  const T v_inf_tr_sq = u_a * u_a + w_tr * w_tr;
  const T v_vf = v_a - p.eps_vf_tr * f.induced_tail - p.l_tr * r_rate;
  const T y_vf = -0.5 * rho * p.s_vf * (p.cla_vf * planar_norm(u_a, w_tr) + abs(v_vf)) * v_vf;
  f.y_vf = clamp_magnitude(y_vf, T(0.5 * rho * p.s_vf * (v_inf_tr_sq + v_vf * v_vf)));
  f.l_vf = p.h_tr * f.y_vf;
  f.n_vf = -p.l_tr * f.y_vf;

  // Horizontal tail (App. B; sign A-12) with its stall clamp; M_ht = l_ht Z_ht for a tail at x = -l_ht.
  const T w_ht = w_a + p.l_ht * q_rate - f.wake_factor * f.induced_main;
  const T z_ht = options.horizontal_tail_sign * 0.5 * rho * p.s_ht * (p.cla_ht * abs(u_a) * w_ht + abs(w_ht) * w_ht);
  f.z_ht = clamp_magnitude(z_ht, T(0.5 * rho * p.s_ht * (u_a * u_a + w_ht * w_ht)));
  f.m_ht = p.l_ht * f.z_ht;
}

// Main- and tail-rotor torques and the yaw inertia of `f`, from its rotor speed and inflow.
template <class T>
void fill_rotor_torques(const Parameters& p, const ModelOptions& options, BasicForces<T>& f) {
  using std::sqrt;
  const double rho = p.rho, r_mr = p.radius_mr;
  const T tip_speed = f.rotor_speed * r_mr;
  const T mu = f.advance_ratio, mu_z = f.inflow_normal;
  const double sigma = p.solidity(options.solidity);

  // Main-rotor torque (App. B): C_T consistent with A4, C_Qmr = C_T (lambda0 - mu_z) + profile.
  const T inflow = p.lambda0 - mu_z;
  f.thrust_coefficient = 2.0 * p.eta_w * p.lambda0 * sqrt(mu * mu + inflow * inflow);
  f.torque_coefficient = f.thrust_coefficient * inflow + p.cd0_mr * sigma / 8.0 * (1.0 + 7.0 / 3.0 * mu * mu);
  f.q_mr = f.torque_coefficient * rho * tip_speed * tip_speed * std::numbers::pi * r_mr * r_mr * r_mr;

  // Tail-rotor profile torque at Omega_tr = n_tr Omega_mr.
  if (options.tail_rotor_torque == ModelOptions::TailRotorTorque::profile) {
    const T omega_tr = p.gear_tr * f.rotor_speed;
    const double r_tr = p.radius_tr;
    f.q_tr = rho * std::numbers::pi * (r_tr * r_tr * r_tr * r_tr * r_tr) * omega_tr * omega_tr * p.cd0_tr *
             p.tail_rotor_solidity() / 8.0;
  } else {
    f.q_tr = 0.0;
  }
  f.yaw_inertia = p.effective_yaw_inertia(options.yaw_inertia);
}

// Flapping speed derivatives of `f`, §2.5 resolved form; paper-literal with the
// paper switches.
template <class T>
void fill_flapping_derivatives(const Parameters& p, const ModelOptions& options, BasicForces<T>& f) {
  const T u_a = f.air.u_a, v_a = f.air.v_a, w_a = f.air.w_a;
  const T tip_speed = f.rotor_speed * p.radius_mr;
  const T mu = f.advance_ratio;
  const double sigma = p.solidity(options.solidity);

  const T flap_scale = 1.0 / (p.tau_e * tip_speed);
  const double sign_mu =
      options.flap_inflow_sign_source == ModelOptions::FlapInflowSignSource::u_a && u_a < 0.0 ? -1.0 : 1.0;
  const T k_z = 16.0 * p.k_mu * mu * mu * sign_mu / (8.0 * mu + p.lift_slope_mr * sigma);  // da1/dmu_z
  const double c_col0 = 2.0 * p.k_mu * (4.0 * p.trim_collective(options) / 3.0 - p.lambda0);  // da1/dmu at delta_col = 0
  const double c_col_per_input = 8.0 * p.k_mu / 3.0;                                           // d(da1/dmu)/d delta_col
  const double s_b = options.lateral_flap_speed_sign;
  f.a1_speed = (k_z * w_a + c_col0 * u_a) * flap_scale;
  f.b1_speed = s_b * c_col0 * v_a * flap_scale;
  f.a1_per_collective = c_col_per_input * u_a * flap_scale;
  f.b1_per_collective = s_b * c_col_per_input * v_a * flap_scale;
  const T speed_ratio = f.rotor_speed / p.omega_nom;
  f.a1_per_lon = p.a_lon_nom / p.tau_e * speed_ratio * speed_ratio;
  f.b1_per_lat = p.b_lat_nom / p.tau_e * speed_ratio * speed_ratio;
}

template <class T, class State>
BasicForces<T> forces_of(const Parameters& p, const ModelOptions& options, const Environment& environment,
                         const BasicAirData<T>& air, const State& x, const T& rotor_speed) {
  using std::sqrt;
  if (!(value_of(rotor_speed) > 0.0) || !std::isfinite(value_of(rotor_speed))) {
    std::ostringstream message;
    message << "helicopter: main-rotor speed " << value_of(rotor_speed) << " rad/s is not positive and finite";
    throw Error(message.str());
  }
  const double rho = p.rho, r_mr = p.radius_mr;
  const T u_a = air.u_a, v_a = air.v_a, w_a = air.w_a;

  BasicForces<T> f;
  f.air = air;
  f.rotor_speed = rotor_speed;
  const T tip_speed = rotor_speed * r_mr;
  f.advance_ratio = planar_norm(u_a, v_a) / tip_speed;  // A5
  f.inflow_normal = w_a / tip_speed;                                  // A6

  // constant induced velocity, or the one of the constant-lambda0 thrust model.
  const T induced_main_model =
      options.induced_velocity_model == ModelOptions::InducedVelocityModel::constant ? T(p.v_imr) : T(p.lambda0 * tip_speed);
  f.induced_main = environment.induced_main_scale * induced_main_model;
  f.induced_tail = environment.induced_tail_scale * p.v_itr;
  f.wake_factor = wake_factor(p, u_a, w_a, f.induced_main);

  // Fuselage, A7-A9, with the downwash sign of A-8.
  const T w_fus = w_a + options.fuselage_downwash_sign * f.induced_main;
  const T v_inf = sqrt(u_a * u_a + v_a * v_a + w_fus * w_fus);
  f.x_fus = -0.5 * rho * p.cd_x * p.s_fus_x * u_a * v_inf;
  f.y_fus = -0.5 * rho * p.cd_y * p.s_fus_y * v_a * v_inf;
  f.z_fus = -0.5 * rho * p.cd_z * p.s_fus_z * w_fus * v_inf;

  fill_tail_forces(p, options, x, f);
  fill_rotor_torques(p, options, f);
  fill_flapping_derivatives(p, options, f);
  return f;
}

}  // namespace

AirData air_data(const Environment& environment, const Eigen::Ref<const Eigen::VectorXd>& x) {
  return air_data_of<double>(environment, x);
}

Forces evaluate_forces(const Parameters& p, const ModelOptions& options, const Environment& environment,
                       const AirData& air, const Eigen::Ref<const Eigen::VectorXd>& x, double rotor_speed) {
  return forces_of(p, options, environment, air, x, rotor_speed);
}

BasicAirData<Dual> dual_air_data(const Environment& environment, const DualState& x) {
  return air_data_of<Dual>(environment, x);
}

BasicForces<Dual> dual_forces(const Parameters& p, const ModelOptions& options, const Environment& environment,
                              const BasicAirData<Dual>& air, const DualState& x, const Dual& rotor_speed) {
  return forces_of(p, options, environment, air, x, rotor_speed);
}

}  // namespace thetad::heli
