#include "apps/thetad/demo_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/riccati.hpp"
#include "core/trim.hpp"

namespace thetad::app {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<double> to_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

}  // namespace

int run_demo(const std::filesystem::path& out) {
  using namespace heli;
  const Helicopter plant;  // nominal parameters, resolved preset, no wind: the controller's model

  // docs/model.md §8.1: at rest on the ground, s = 1, rotor speed from T_mr = m g.
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(kStateDim);
  x0(kS) = 1.0;
  const DesignDefaults defaults = plant.design_defaults();  // the paper's Q, R and u0 = [m g, 0, 0, 0, 0]
  const Eigen::VectorXd& u0 = defaults.input;
  const auto [A0, g0] = plant.sdc(x0, u0);
  const Eigen::MatrixXd Q = defaults.state_weights.asDiagonal();
  const Eigen::MatrixXd R = defaults.input_weights.asDiagonal();

  std::printf("thetad demo: the paper-sized Riccati problem at the initial state (n = %d, m = %d)\n",
              kStateDim, kInputDim);
  std::printf("  rotor speed at rest with T_mr = m g: %.3f rad/s\n", plant.rotor_speed(x0, u0(kTmr)));

  auto start = std::chrono::steady_clock::now();
  const CareResult care = solve_care(A0, g0, Q, R);
  const double care_seconds = seconds_since(start);
  const double slowest = care.closed_loop_eigenvalues.real().maxCoeff();
  const double fastest = care.closed_loop_eigenvalues.real().minCoeff();
  const Eigen::VectorXd feed_forward = -care.K.col(kS);
  std::printf("  solve_care (%s): relative residual %.2e, %.0f us\n",
              care.sign_iterations > 0 ? "matrix sign function" : "Laub-Schur", care.relative_residual, care_seconds * 1e6);
  std::printf("  closed-loop eigenvalues: real parts in [%.4f, %.4f]\n", fastest, slowest);
  std::printf("  bias feed-forward -K(:, s): T_mr %.4f N (m g = %.3f N), d_ped %.5f, d_lat %.5f rad\n",
              feed_forward(kTmr), u0(kTmr), feed_forward(kPed), feed_forward(kLat));

  // The online SDRE's warm start: Newton-Kleinman from a 1 % perturbed solution.
  const Eigen::MatrixXd P_start = care.P * 1.01;
  start = std::chrono::steady_clock::now();
  const CareResult newton = solve_care_newton(A0, g0, Q, R, P_start);
  const double newton_seconds = seconds_since(start);
  const double agreement = (newton.P - care.P).norm() / care.P.norm();
  std::printf("  solve_care_newton from 1.01 P: %d iterations, residual %.2e, |P_N - P|/|P| = %.2e, %.0f us\n",
              newton.iterations, newton.relative_residual, agreement, newton_seconds * 1e6);

  start = std::chrono::steady_clock::now();
  const Trim hover = find_trim(plant, TrimCondition::hover(3.5));
  const double trim_seconds = seconds_since(start);
  std::printf("hover trim at 3.5 m (Ipopt, %d iterations, %.0f ms, |f| = %.1e):\n", hover.iterations,
              trim_seconds * 1e3, hover.residual);
  std::printf("  T_mr %.4f N, rotor speed %.3f rad/s, roll %.4f deg, b1 %.5f rad, d_ped %.5f rad, d_lat %.6f rad\n",
              hover.input(kTmr), hover.rotor_speed, hover.state(kPhi) * 180.0 / 3.141592653589793,
              hover.state(kB1), hover.input(kPed), hover.input(kLat));

  nlohmann::json report;
  report["riccati"] = {{"n", kStateDim},
                       {"m", kInputDim},
                       {"relative_residual", care.relative_residual},
                       {"seconds", care_seconds},
                       {"slowest_closed_loop_real_part", slowest},
                       {"fastest_closed_loop_real_part", fastest},
                       {"diag_T0", to_vector(care.P.diagonal())},
                       {"bias_feed_forward", to_vector(feed_forward)}};
  report["newton_kleinman"] = {{"iterations", newton.iterations},
                               {"relative_residual", newton.relative_residual},
                               {"relative_difference_to_schur", agreement},
                               {"seconds", newton_seconds}};
  report["hover_trim"] = {{"altitude_m", 3.5},
                          {"state", to_vector(hover.state)},
                          {"input", to_vector(hover.input)},
                          {"rotor_speed_rad_s", hover.rotor_speed},
                          {"residual", hover.residual},
                          {"ipopt_status", hover.solver_status},
                          {"iterations", hover.iterations}};
  const auto path = out / "demo.json";
  write_file_atomically(path, report.dump(2) + "\n");
  std::printf("wrote %s\n", path.c_str());
  return 0;
}

}  // namespace thetad::app
