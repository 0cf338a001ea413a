#include "experiment/demo_diagnostics.hpp"

#include <chrono>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/helicopter/helicopter.hpp"
#include "core/riccati.hpp"
#include "experiment/provenance.hpp"

namespace thetad {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<double> to_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// printf into a std::string: the figures read as they always have on the terminal.
template <class... Args>
std::string line(const char* format, Args... args) {
  const int size = std::snprintf(nullptr, 0, format, args...);
  std::string text(static_cast<std::size_t>(size) + 1, '\0');
  std::snprintf(text.data(), text.size(), format, args...);
  text.pop_back();
  return text;
}

}  // namespace

DemoDiagnostics demo_diagnostics() {
  using namespace heli;
  const Helicopter plant;  // nominal parameters, resolved preset, no wind: the controller's model
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(kStateDim);
  x0(kS) = 1.0;
  const DesignDefaults defaults = plant.design_defaults();  // the paper's Q, R and u0 = [m g, 0, 0, 0, 0]
  const Eigen::VectorXd& u0 = defaults.input;
  const auto [A0, g0] = plant.sdc(x0, u0);
  const Eigen::MatrixXd Q = defaults.state_weights.asDiagonal();
  const Eigen::MatrixXd R = defaults.input_weights.asDiagonal();

  DemoDiagnostics d;
  d.hover_thrust = u0(kTmr);
  d.rotor_speed_at_rest = plant.rotor_speed(x0, u0(kTmr));
  auto start = std::chrono::steady_clock::now();
  d.care = solve_care(A0, g0, Q, R);
  d.care_seconds = seconds_since(start);
  d.bias_feed_forward = -d.care.K.col(kS);

  start = std::chrono::steady_clock::now();
  d.newton = solve_care_newton(A0, g0, Q, R, d.care.P * 1.01);
  d.newton_seconds = seconds_since(start);
  d.newton_difference = (d.newton.P - d.care.P).norm() / d.care.P.norm();

  start = std::chrono::steady_clock::now();
  d.hover = find_trim(plant, TrimCondition::hover(d.hover_altitude));
  d.trim_seconds = seconds_since(start);
  return d;
}

std::string demo_text(const DemoDiagnostics& d) {
  using namespace heli;
  const Eigen::VectorXcd& poles = d.care.closed_loop_eigenvalues;
  const Eigen::VectorXd& ff = d.bias_feed_forward;
  std::string text;
  text += line("thetad demo: the paper-sized Riccati problem at the initial state (n = %d, m = %d)\n", kStateDim,
               kInputDim);
  text += line("  rotor speed at rest with T_mr = m g: %.3f rad/s\n", d.rotor_speed_at_rest);
  text += line("  solve_care (%s): relative residual %.2e, %.0f us\n",
               d.care.sign_iterations > 0 ? "matrix sign function" : "Laub-Schur", d.care.relative_residual,
               d.care_seconds * 1e6);
  text += line("  closed-loop eigenvalues: real parts in [%.4f, %.4f]\n", poles.real().minCoeff(), poles.real().maxCoeff());
  text += line("  bias feed-forward -K(:, s): T_mr %.4f N (m g = %.3f N), d_ped %.5f, d_lat %.5f rad\n", ff(kTmr),
               d.hover_thrust, ff(kPed), ff(kLat));
  text += line("  solve_care_newton from 1.01 P: %d iterations, residual %.2e, |P_N - P|/|P| = %.2e, %.0f us\n",
               d.newton.iterations, d.newton.relative_residual, d.newton_difference, d.newton_seconds * 1e6);
  text += line("hover trim at %.1f m (Ipopt, %d iterations, %.0f ms, |f| = %.1e):\n", d.hover_altitude,
               d.hover.iterations, d.trim_seconds * 1e3, d.hover.residual);
  text += line("  T_mr %.4f N, rotor speed %.3f rad/s, roll %.4f deg, b1 %.5f rad, d_ped %.5f rad, d_lat %.6f rad\n",
               d.hover.input(kTmr), d.hover.rotor_speed, d.hover.state(kPhi) * 180.0 / std::numbers::pi,
               d.hover.state(kB1), d.hover.input(kPed), d.hover.input(kLat));
  return text;
}

nlohmann::ordered_json demo_json(const DemoDiagnostics& d) {
  const Eigen::VectorXcd& poles = d.care.closed_loop_eigenvalues;
  nlohmann::ordered_json report;
  report["riccati"] = {{"n", d.care.P.rows()},
                       {"m", d.care.K.rows()},
                       {"relative_residual", d.care.relative_residual},
                       {"seconds", d.care_seconds},
                       {"slowest_closed_loop_real_part", poles.real().maxCoeff()},
                       {"fastest_closed_loop_real_part", poles.real().minCoeff()},
                       {"diag_T0", to_vector(d.care.P.diagonal())},
                       {"bias_feed_forward", to_vector(d.bias_feed_forward)}};
  report["newton_kleinman"] = {{"iterations", d.newton.iterations},
                               {"relative_residual", d.newton.relative_residual},
                               {"relative_difference_to_schur", d.newton_difference},
                               {"seconds", d.newton_seconds}};
  report["hover_trim"] = {{"altitude_m", d.hover_altitude},
                          {"state", to_vector(d.hover.state)},
                          {"input", to_vector(d.hover.input)},
                          {"rotor_speed_rad_s", d.hover.rotor_speed},
                          {"residual", d.hover.residual},
                          {"ipopt_status", d.hover.solver_status},
                          {"iterations", d.hover.iterations}};
  report["build"] = to_json(build_info());
  return report;
}

}  // namespace thetad
