#pragma once

// Newton–Kleinman with a fixed number of steps: the SDRE's capped mode (controllers/sdre.hpp) and
// the step `thetad export` writes for a flight computer (export/onboard/sdre_step.hpp), which must
// do the same arithmetic so that the two can be compared to rounding. Each step solves the
// Lyapunov equation of the closed loop of the current P,
//     (A − G Pk)'Δ + Δ(A − G Pk) + Res(Pk) = 0,   Pk+1 = Pk + Δ,   G = B R⁻¹ B',
// as core/newton_kleinman.hpp does, but always exactly `steps` of them: no chord steps and no
// stopping rule, so that the work per sample is fixed (what a real-time budget needs). How far the
// result is from the Riccati solution is reported, not acted on: ρ of the returned P, the residual
// relative to the terms that cancel in it (newton_kleinman.hpp).

#include <Eigen/Dense>

#include "core/care_weights.hpp"
#include "core/lyapunov.hpp"

namespace thetad {

// Every buffer is sized at construction; solve() allocates nothing unless it throws. Not
// thread-safe per object.
class CappedNewtonKleinman {
 public:
  // Q n×n symmetric positive semi-definite, R m×m symmetric positive definite (checked, as by
  // solve_care); 1 ≤ steps.
  CappedNewtonKleinman(const Eigen::Ref<const Eigen::MatrixXd>& Q, const Eigen::Ref<const Eigen::MatrixXd>& R,
                       int steps);

  // P after `steps` Newton steps from P0 (symmetrized first) for (A, B); it lives in this object
  // until the next call. Throws thetad::Error when A, B or P0 do not fit or are not finite, when
  // the closed loop of an iterate is not Hurwitz (Kleinman's iteration needs P0 stabilizing; the
  // message gives the step and the largest Re λ) or when a Lyapunov solve fails.
  const Eigen::MatrixXd& solve(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                               const Eigen::Ref<const Eigen::MatrixXd>& P0);

  int steps() const { return steps_; }
  // ρ of the P of the last successful solve().
  double last_residual_to_terms() const { return rho_; }

 private:
  // WP_ and Res_ of P_; returns ρ(P_).
  double evaluate(const Eigen::Ref<const Eigen::MatrixXd>& A);

  care::Weights weights_;
  Eigen::MatrixXd R_;  // as given: only for check_inputs' sizes
  int steps_;
  LyapunovWorkspace lyapunov_;
  Eigen::MatrixXd P_, WP_, Res_, closed_loop_, delta_, WPWPt_;
  double rho_ = 0.0;
};

}  // namespace thetad
