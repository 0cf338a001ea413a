#pragma once

// Eq. (35) computed the slow, independent way: the series written out with S1, S2 and G0 as n×n
// matrices and one Lyapunov solve per piece (ThetaDController::series_expansion, the tuner's cold
// path), none of control()'s T1 basis, low-rank sums, compact products, reuse between passes or
// partial last term. The reference the θ–D step tests hold control() to.

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "controllers/theta_d.hpp"
#include "core/sdc_plant.hpp"

namespace thetad::testing {

// u = −R⁻¹ Bᵀ(x; guess) ΣT_i(x; guess, t) v with the controller's settings and frozen system.
inline Eigen::VectorXd reference_law(ThetaDController& controller, const SdcPlant& model, const Eigen::VectorXd& x,
                                     const Eigen::VectorXd& guess, const Eigen::VectorXd& v, double t) {
  const ThetaDSettings& s = controller.settings();
  Eigen::VectorXd e(s.terms - 1);
  for (Eigen::Index i = 0; i < e.size(); ++i) e[i] = perturbation_factor(s.k[i], s.l[i], t - controller.start_time());
  const Eigen::MatrixXd P = controller.series_expansion(x, guess).evaluate(e);
  const Eigen::MatrixXd B = model.sdc(x, guess).B;
  return -s.R.llt().solve(B.transpose() * (P * v));
}

// The fixed point of docs/model.md §6.2 on reference_law: `passes` passes from the last applied input.
inline Eigen::VectorXd reference_control(ThetaDController& controller, const SdcPlant& model, const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& previous, const Eigen::VectorXd& v, double t,
                                         int passes) {
  Eigen::VectorXd u = previous;
  for (int pass = 0; pass < passes; ++pass) u = reference_law(controller, model, x, u, v, t);
  return u;
}

}  // namespace thetad::testing
