#pragma once

#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "core/care_result.hpp"
#include "core/trim.hpp"

namespace thetad {

// What `thetad demo` (the first thing `make demo` runs) shows before anything flies: the
// foundation of every comparison, checked at the paper's problem size on the nominal X-Cell. At
// rest on the ground (s = 1, T_mr = m g: docs/model.md §8.1) the CARE with the paper's Q, R, its
// Newton–Kleinman solution from a 1 % perturbed start (the online SDRE's warm start), and the
// hover trim at 3.5 m by Ipopt.
struct DemoDiagnostics {
  double hover_thrust = 0.0;         // N: m g, the design input u0's T_mr
  double rotor_speed_at_rest = 0.0;  // rad/s with T_mr = m g
  CareResult care;                   // solve_care at the initial state
  double care_seconds = 0.0;
  Eigen::VectorXd bias_feed_forward;  // −K(:, s): what the bias column s = 1 commands
  CareResult newton;                  // solve_care_newton from 1.01 P
  double newton_seconds = 0.0;
  double newton_difference = 0.0;  // ‖P_N − P‖_F / ‖P‖_F
  double hover_altitude = 3.5;     // m
  Trim hover;
  double trim_seconds = 0.0;
};

// Computes them (about a second, most of it Ipopt's); throws thetad::Error as the solvers do.
DemoDiagnostics demo_diagnostics();

// The lines `thetad demo` prints, each ending in a newline.
std::string demo_text(const DemoDiagnostics& diagnostics);

// demo.json: the figures, and the build that computed them.
nlohmann::ordered_json demo_json(const DemoDiagnostics& diagnostics);

}  // namespace thetad
