#pragma once

// Newton–Kleinman for the CARE A'P + PA − P B R⁻¹ B' P + Q = 0 (Kleinman 1968) from a warm start
// P0 that stabilizes A − G P0, G = B R⁻¹ B': each step solves the Lyapunov equation
// (A − G Pk)'Δ + Δ(A − G Pk) + Res(Pk) = 0 and Pk+1 = Pk + Δ.
//
// Convergence is decided on the P that is returned. The iteration takes at least one step and stops
// when the residual of that P relative to the terms that cancel in it,
//     ρ(P) = ‖Res(P)‖_F / (‖Q‖_F + 2‖A'P‖_F + ‖PGP‖_F),
// is at most the tolerance and the last step ‖Δ‖_F is within tolerance·max(1, ‖P‖_F) or has stopped
// shrinking (the rounding level of the equation). CareResult::relative_residual is ‖Res(P)‖_F /
// max(1, ‖Q‖_F) of that same P. Why these two tests: on the paper's problem the exact solution
// rounded to double has ‖Res‖/‖Q‖ ≈ 1e-10 … 1e-7 (the terms are 1e7 times larger than Q and
// cancel), so a tolerance relative to Q cannot be met, while ρ of that rounded solution is at
// rounding level; and any residual is nearly blind to errors of P along the s-mode, which the
// Newton step measures. When ρ stops decreasing above the tolerance once the steps have settled,
// or max_iterations steps do not get there, it throws and says so.

#include <Eigen/Dense>

#include "core/care_result.hpp"
#include "core/care_weights.hpp"
#include "core/lyapunov.hpp"

namespace thetad {

// One Newton–Kleinman solver for fixed weights Q, R and fixed sizes: the SDRE's warm step. Every
// buffer and LAPACK workspace is sized at construction; solve() allocates nothing unless it throws.
// Per call: one real Schur form of A − G Pk per step (its eigenvalues tell whether P0 stabilizes)
// and one eigenvalue computation of the final closed loop. Not thread-safe per object.
class NewtonKleinmanSolver {
 public:
  // Q n×n symmetric positive semi-definite, R m×m symmetric positive definite (checked, as by
  // solve_care); tolerance > 0 on ρ and on the relative step; max_iterations ≥ 1 steps.
  NewtonKleinmanSolver(const Eigen::Ref<const Eigen::MatrixXd>& Q, const Eigen::Ref<const Eigen::MatrixXd>& R,
                       double tolerance = 1e-12, int max_iterations = 50);

  // The stabilizing solution for (A, B) from P0. The result lives in this object until the next
  // call. Throws thetad::Error when A or B do not fit or are not finite, when P0 does not fit, is
  // not finite or does not stabilize (the message gives the largest Re λ of A − G P0), when a
  // Lyapunov step fails, when ρ stalls above the tolerance or when max_iterations steps do not
  // reach it (the message gives ρ and the tolerance), and when the final P does not stabilize.
  const CareResult& solve(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                          const Eigen::Ref<const Eigen::MatrixXd>& P0);

  double tolerance() const { return tolerance_; }
  // ρ of the P of the last successful solve().
  double last_residual_to_terms() const { return rho_; }

 private:
  // WP_ and Res_ of P_; returns ρ(P_).
  double evaluate(const Eigen::Ref<const Eigen::MatrixXd>& A);

  care::Weights weights_;
  Eigen::MatrixXd R_;  // as given: only for check_inputs' sizes
  double tolerance_;
  int max_iterations_;
  double q_norm_;
  Eigen::Index n_, m_;
  LyapunovWorkspace lyapunov_;
  Eigen::MatrixXd P_, WP_, Res_, Ak_, delta_, WPWPt_;
  double rho_ = 0.0;
  CareResult result_;
};

// Newton–Kleinman once, for a one-off equation: NewtonKleinmanSolver(Q, R, tolerance,
// max_iterations).solve(A, B, P0), with the same errors (and those of Q and R); a failure names the
// precondition the data break when one is found (care_diagnosis.hpp), as solve_care does.
CareResult solve_care_newton(const Eigen::Ref<const Eigen::MatrixXd>& A,
                             const Eigen::Ref<const Eigen::MatrixXd>& B,
                             const Eigen::Ref<const Eigen::MatrixXd>& Q,
                             const Eigen::Ref<const Eigen::MatrixXd>& R,
                             const Eigen::Ref<const Eigen::MatrixXd>& P0,
                             double tolerance = 1e-12, int max_iterations = 50);

}  // namespace thetad
