#pragma once

// Newton–Kleinman for the CARE A'P + PA − P B R⁻¹ B' P + Q = 0 (Kleinman 1968) from a warm start
// P0 that stabilizes A − G P0, G = B R⁻¹ B': each step solves the Lyapunov equation
// (A − G Pk)'Δ + Δ(A − G Pk) + Res(Pk) = 0 and Pk+1 = Pk + Δ.
//
// Convergence is decided on the P that is returned. The iteration takes at least one step and stops
// when the residual of that P relative to the terms that cancel in it,
//     ρ(P) = ‖Res(P)‖_F / (‖Q‖_F + 2‖A'P‖_F + ‖PGP‖_F),
// is at most the tolerance and the last step ‖Δ‖_F is within tolerance·max(1, ‖P‖_F) or, for a
// Newton step, has stopped shrinking (the rounding level of the equation). CareResult::relative_residual is ‖Res(P)‖_F /
// max(1, ‖Q‖_F) of that same P. Why these two tests: on the paper's problem the exact solution
// rounded to double has ‖Res‖/‖Q‖ ≈ 1e-10 … 1e-7 (the terms are 1e7 times larger than Q and
// cancel), so a tolerance relative to Q cannot be met, while ρ of that rounded solution is at
// rounding level; and any residual is nearly blind to errors of P along the s-mode, which the
// Newton step measures. When ρ stops decreasing above the tolerance once the Newton steps have
// settled, or max_iterations steps do not get there, it throws and says so.

#include <Eigen/Dense>

#include "core/care_result.hpp"
#include "core/care_weights.hpp"
#include "core/lyapunov.hpp"
#include "core/lyapunov_certificate.hpp"

namespace thetad {

// One Newton–Kleinman solver for fixed weights Q, R and fixed sizes: the SDRE's warm step. Every
// buffer is sized at construction; solve() allocates nothing unless it throws. Not thread-safe per
// object.
//
// The Schur form of a closed loop is most of a step's cost, so a step reuses the one this object
// holds while that pays (a chord step, Δ from the Lyapunov operator of an earlier closed loop).
// The returned P is shown to stabilize as `StabilityProof` says: by the closed-loop spectrum,
// computed once per call, at the end, whose Schur form is then the operator of the next call's
// first step; or by a Lyapunov certificate when it holds, which leaves the Schur form of the last
// Newton step held, of this call or of one any number of calls before. A chord step that does not
// lower ρ is undone and the step retaken with a Schur form of the current closed loop (a Newton
// step); so is every step after one that did not shrink the step twentyfold (from a call's third
// step on, when there is a ratio of steps): that is what renews a held Schur form grown too old. When
// the iteration fails after chord steps (a P that does not stabilize, a stall, too many steps), the
// call starts again from P0 with Newton steps only. The stopping rule above is the same for both
// kinds of step; only a Newton step can stall.
class NewtonKleinmanSolver {
 public:
  // Q n×n symmetric positive semi-definite, R m×m symmetric positive definite (checked, as by
  // solve_care); tolerance > 0 on ρ and on the relative step; max_iterations ≥ 1 steps.
  NewtonKleinmanSolver(const Eigen::Ref<const Eigen::MatrixXd>& Q, const Eigen::Ref<const Eigen::MatrixXd>& R,
                       double tolerance = 1e-12, int max_iterations = 50,
                       StabilityProof proof = StabilityProof::spectrum);

  // The stabilizing solution for (A, B) from P0. The result lives in this object until the next
  // call. Throws thetad::Error when A or B do not fit or are not finite, when P0 does not fit, is
  // not finite or does not stabilize (the message gives the largest Re λ of A − G P0; the first
  // step of a call with a held Schur form does not look at P0's closed loop, so a P0 that does
  // not stabilize may also end in the errors that follow), when a Lyapunov step fails, when ρ
  // stalls above the tolerance or when max_iterations steps do not reach it (the message gives ρ
  // and the tolerance), and when the final P does not stabilize.
  const CareResult& solve(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                          const Eigen::Ref<const Eigen::MatrixXd>& P0);

  // Drops the held Schur form: the next solve() starts with a Newton step, as a new solver does,
  // so that a result does not depend on the calls before (a controller's reset()).
  void forget() { held_ = false; }

  double tolerance() const { return tolerance_; }
  // ρ of the P of the last successful solve().
  double last_residual_to_terms() const { return rho_; }
  // Schur forms of the last successful solve(): its Newton steps plus the final one of the
  // returned P's closed loop unless the Lyapunov certificate held (so 0 when every step reused a
  // held Schur form and it held).
  int last_schur_forms() const { return last_schur_forms_; }
  // The last successful solve() proved stability by the Lyapunov certificate, not the spectrum.
  bool last_certified() const { return last_certified_; }

 private:
  // An iterate and what is computed from it.
  struct Iterate {
    Eigen::MatrixXd P, WP, Res;
    double rho = 0.0;
  };
  // WP and Res of it.P; sets it.rho = ρ(it.P).
  void evaluate(const Eigen::Ref<const Eigen::MatrixXd>& A, Iterate& it);
  // Schur form of A − G·P of `it` into lyapunov_.
  void factor_closed_loop(const Eigen::Ref<const Eigen::MatrixXd>& A, const Iterate& it);
  // The iteration from P0 to current_ and the proof that it stabilizes (the Schur form of its
  // closed loop or the certificate), chord steps allowed from the start when `chord` (a Schur form
  // is held); adds its steps to `steps`, and has max_iterations_ of its own. False, after a chord
  // step, on any failure but a Lyapunov solve's; throws otherwise.
  bool iterate(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& P0, bool chord,
               int& steps);

  care::Weights weights_;
  Eigen::MatrixXd R_;  // as given: only for check_inputs' sizes
  double tolerance_;
  int max_iterations_;
  StabilityProof proof_;
  Eigen::Index n_, m_;
  LyapunovWorkspace lyapunov_;
  LyapunovCertificate certificate_;
  bool certified_ = false;  // the last iterate()'s P was proved stabilizing by certificate_
  int schur_forms_ = 0;     // of the current solve()
  bool held_ = false;  // lyapunov_ holds the Schur form of a stable closed loop of an earlier P
  Iterate current_, next_;
  Eigen::MatrixXd Ak_, delta_, WPWPt_;
  // What the last successful solve() reports.
  double rho_ = 0.0;
  int last_schur_forms_ = 0;
  bool last_certified_ = false;
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
