#pragma once

// Linear models of an SdcPlant at an operating point and the LQR gain designed on them: the
// building blocks of the hover-point LQR (lqr.hpp) and of gain scheduling over a grid of trims.

#include <Eigen/Core>

#include "core/helicopter/helicopter.hpp"
#include "core/riccati.hpp"
#include "core/sdc_plant.hpp"
#include "core/trim.hpp"

namespace thetad {

// xdot ≈ f(x*, u*) + A (x − x*) + B (u − u*).
struct Linearization {
  Eigen::MatrixXd A;  // ∂f/∂x, n×n
  Eigen::MatrixXd B;  // ∂f/∂u, n×m
};

// The Jacobians of plant.f at (x, u) by central differences, step h_j = relative_step·max(1, |z_j|)
// per coordinate. The default balances truncation (O(h²)) against rounding (O(ε/h)) for an f
// evaluated to full precision (the helicopter's rotor-speed root is solved to 1e-12 relative).
// f is evaluated as it is, central differences of the exact model rather than of the SDC form
// (F(x) x is not the linearization: F depends on x).
Linearization linearize(const SdcPlant& plant, const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                        double relative_step = 6e-6);

// Where a linear controller is designed: the state, the input, and the tracking vector V* the plant
// holds there when it tracks its reference (for the helicopter V_track at the trim: zero position
// and integral errors, the trim's velocities, attitude, rates and flapping, s = 1). A linear
// controller acts on V − V* and adds u*.
struct OperatingPoint {
  Eigen::VectorXd state;
  Eigen::VectorXd input;
  Eigen::VectorXd tracking;
};

// The operating point of a helicopter trim: V* = tracking_vector(x*, reference at x*).
OperatingPoint operating_point(const heli::Helicopter& model, const Trim& trim);

// LQR on the first `design_states` states of the linearization at `point` (the trailing states,
// e.g. the helicopter's bias state s, are constants that a linear design leaves out):
// CARE with A, B, Q, R restricted to them. The result's K (m × design_states) gives
// u = u* − K (V − V*)[0, design_states). Throws thetad::Error when the CARE has no stabilizing
// solution (the linearization is not stabilizable or Q leaves an unstable mode unobserved).
CareResult design_lqr(const SdcPlant& plant, const OperatingPoint& point, const Eigen::MatrixXd& Q,
                      const Eigen::MatrixXd& R, Eigen::Index design_states);

}  // namespace thetad
