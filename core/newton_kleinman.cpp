#include "core/newton_kleinman.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "core/care_diagnosis.hpp"
#include "core/error.hpp"

namespace thetad {
namespace {

using care::fail;
using care::num;
using Eigen::Index;
using Eigen::MatrixXd;
using MatrixRef = Eigen::Ref<const MatrixXd>;

// A chord step follows a step that shrank at least this much relative to the one before it.
// Measured on scenario-I states (docs/performance.md): 0.01 takes 3 Schur forms per warm call on
// most states, 0.05 1–3 for 5–7 steps, 0.3 mostly 1 but up to 15 steps, more than the tests allow.
constexpr double kChordContraction = 0.05;

}  // namespace

NewtonKleinmanSolver::NewtonKleinmanSolver(const MatrixRef& Q, const MatrixRef& R, double tolerance,
                                           int max_iterations, StabilityProof proof)
    : R_(R), tolerance_(tolerance), max_iterations_(max_iterations), proof_(proof), n_(Q.rows()), m_(R.rows()),
      lyapunov_(std::max<Index>(Q.rows(), 1)), certificate_(Q.rows()) {
  if (n_ == 0 || Q.cols() != n_) fail("Q must be square and non-empty, but Q is " + care::shape(Q));
  if (m_ == 0 || R.cols() != m_) fail("R must be square and non-empty, but R is " + care::shape(R));
  if (!Q.allFinite()) fail("Q has a non-finite entry (NaN or Inf)");
  if (!R.allFinite()) fail("R has a non-finite entry (NaN or Inf)");
  if (!(tolerance > 0.0) || max_iterations < 1)
    fail("Newton–Kleinman needs tolerance > 0 and max_iterations ≥ 1 (got " + num(tolerance) + ", " +
         std::to_string(max_iterations) + ")");
  weights_ = care::prepare_weights(Q, R);
  weights_.W.resize(m_, n_);
  for (Iterate* it : {&current_, &next_}) {
    it->P.resize(n_, n_);
    it->WP.resize(m_, n_);
    it->Res.resize(n_, n_);
  }
  Ak_.resize(n_, n_);
  delta_.resize(n_, n_);
  WPWPt_.resize(m_, m_);
  result_.P.resize(n_, n_);
  result_.K.resize(m_, n_);
  result_.closed_loop_eigenvalues.resize(n_);
}

void NewtonKleinmanSolver::evaluate(const MatrixRef& A, Iterate& it) {
  it.WP.noalias() = weights_.W * it.P;
  const double AtP_norm = care::care_residual(A, weights_, it.P, it.WP, it.Res);
  WPWPt_.noalias() = it.WP * it.WP.transpose();  // ‖PGP‖_F = ‖(WP)'(WP)‖_F = ‖(WP)(WP)'‖_F, m×m
  it.rho = care::residual_to_terms(care::frobenius_norm(it.Res), weights_.q_norm, AtP_norm, care::frobenius_norm(WPWPt_));
}

void NewtonKleinmanSolver::factor_closed_loop(const MatrixRef& A, const Iterate& it) {
  Ak_ = A;
  Ak_.noalias() -= weights_.W.transpose() * it.WP;
  lyapunov_.factor(Ak_);
  ++schur_forms_;
}

bool NewtonKleinmanSolver::iterate(const MatrixRef& A, const MatrixRef& P0, bool chord, int& steps) {
  certified_ = false;
  current_.P = P0;
  care::symmetrize(current_.P);
  evaluate(A, current_);
  bool newton_next = !chord;
  bool chord_taken = false;
  double previous_rho = std::numeric_limits<double>::infinity();
  double step = std::numeric_limits<double>::infinity();
  double previous_step = std::numeric_limits<double>::infinity();
  bool last_was_newton = false;
  bool retake = false;  // the last chord step was undone: take it again as a Newton step
  int accepted = 0;     // steps that moved P; `steps` counts an undone chord step too
  const int first_step = steps;
  for (;;) {
    const double rho = current_.rho;
    if (!std::isfinite(rho) && chord_taken) return false;
    if (!std::isfinite(rho)) fail("Newton–Kleinman: the residual is not finite at step " + std::to_string(steps));
    // At least one step: a residual is blind to some errors of P (ill-conditioned directions), the
    // Newton step measures them. Then stop on the returned P's own ρ once the step is within the
    // tolerance or, after a Newton step, has stopped shrinking, i.e. reached the rounding level of
    // this equation. A chord step that stops shrinking says only that its Schur form is too old.
    if (accepted > 0 && !retake) {
      const bool small = step <= tolerance_ * std::max(1.0, care::frobenius_norm(current_.P));
      const bool stagnant = step > 0.5 * previous_step;
      if (rho <= tolerance_ && (small || (stagnant && last_was_newton))) break;
      const bool stalled = last_was_newton && (small || stagnant) && !(rho < previous_rho);
      if (stalled && chord_taken) return false;
      if (stalled)
        fail("Newton–Kleinman stalled above the tolerance: the residual ρ went from " + num(previous_rho) +
             " to " + num(rho) + " at step " + std::to_string(steps) + " (tolerance " + num(tolerance_) + ")");
      // A chord step shrinks the step by about twice the last ratio of steps: worth it only when
      // that is small, else the Schur form is renewed. A call's first step, when a Newton step, has
      // no ratio yet.
      newton_next = !chord || !(step <= kChordContraction * previous_step) || (last_was_newton && accepted == 1);
    }
    const int taken = steps - first_step;
    if (taken == max_iterations_ && chord_taken) return false;
    if (taken == max_iterations_)
      fail("Newton–Kleinman did not converge in " + std::to_string(taken) + " iterations (residual ρ " + num(rho) +
           ", last relative step " + num(step / std::max(1.0, care::frobenius_norm(current_.P))) + ", tolerance " +
           num(tolerance_) + ")");
    if (newton_next) {
      try {
        factor_closed_loop(A, current_);
      } catch (const Error& e) {
        fail("Newton–Kleinman step " + std::to_string(steps + 1) + ": " + e.what());
      }
      // The closed loop of Pk is stable for every k when P0 stabilizes (Kleinman): its Schur
      // form, needed for the step anyway, checks P0 and guards against rounding later.
      const double max_real = lyapunov_.max_real_eigenvalue();
      if (!(max_real < 0.0)) {
        if (chord_taken) return false;
        fail(accepted == 0 ? "Newton–Kleinman: P0 is not stabilizing (largest Re λ of A − G P0 is " + num(max_real) + ")"
                           : "Newton–Kleinman: A − G P lost stability at step " + std::to_string(accepted) +
                                 " (largest Re λ " + num(max_real) + ")");
      }
    }
    try {
      lyapunov_.solve(current_.Res, delta_);
    } catch (const Error& e) {
      fail("Newton–Kleinman step " + std::to_string(steps + 1) + ": " + e.what());
    }
    ++steps;
    next_.P = current_.P + delta_;
    care::symmetrize(next_.P);
    evaluate(A, next_);
    if (!newton_next && !(next_.rho <= tolerance_ || next_.rho < rho)) {
      newton_next = true;  // undone: the held Schur form is too far from this closed loop
      retake = true;
      continue;
    }
    retake = false;
    chord_taken = chord_taken || !newton_next;
    last_was_newton = newton_next;
    newton_next = false;
    ++accepted;
    previous_step = step;
    step = care::frobenius_norm(delta_);
    previous_rho = rho;
    std::swap(current_, next_);
  }

  // The certificate, a few percent of a Schur form, when asked for and when it holds; the held
  // Schur form then stays that of the last Newton step.
  if (proof_ == StabilityProof::lyapunov &&
      certificate_.proves_hurwitz(A, weights_, current_.P, current_.WP, current_.Res)) {
    certified_ = true;
    return true;
  }
  // Else the one spectrum of the call: the closed loop of the P returned, whose Schur form the
  // next call's first step uses.
  try {
    factor_closed_loop(A, current_);
  } catch (const Error& e) {
    fail(std::string("the closed loop of the solution: ") + e.what());
  }
  const double max_real = lyapunov_.max_real_eigenvalue();
  if (max_real < 0.0) return true;
  if (chord_taken) return false;
  fail("the solution is not stabilizing: A − BK has an eigenvalue with Re λ = " + num(max_real) +
       care::kStabilizabilityHint);
}

const CareResult& NewtonKleinmanSolver::solve(const MatrixRef& A, const MatrixRef& B, const MatrixRef& P0) {
  care::check_inputs(A, B, weights_.Q, R_);
  if (P0.rows() != n_ || P0.cols() != n_) fail("P0 is " + care::shape(P0) + " but A is " + care::shape(A));
  if (!P0.allFinite()) fail("P0 has a non-finite entry (NaN or Inf)");
  care::set_input_matrix(weights_, B);
  // A throw below leaves no Schur form held: the next call then starts with a Newton step.
  const bool held = held_;
  held_ = false;
  schur_forms_ = 0;
  int steps = 0;
  // Chord steps can lead to a P that no longer stabilizes or from which Newton stalls (the held
  // Schur form was too far, seen on the transient at the start of scenario I): the call then starts
  // again from P0 with Newton steps only, Kleinman's iteration, which keeps every closed loop stable.
  if (!iterate(A, P0, held, steps)) iterate(A, P0, false, steps);
  held_ = true;
  rho_ = current_.rho;
  last_schur_forms_ = schur_forms_;
  last_certified_ = certified_;
  result_.P = current_.P;
  result_.K = current_.WP;
  weights_.L.transpose().triangularView<Eigen::Upper>().solveInPlace(result_.K);
  if (certified_) {
    leave_spectrum_uncomputed(result_);
  } else {
    for (Index i = 0; i < n_; ++i)
      result_.closed_loop_eigenvalues(i) = {lyapunov_.eigenvalues_real()(i), lyapunov_.eigenvalues_imag()(i)};
  }
  result_.relative_residual = care::relative_to_q(care::frobenius_norm(current_.Res), weights_);
  result_.iterations = steps;
  result_.sign_iterations = 0;
  return result_;
}

CareResult solve_care_newton(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R,
                             const MatrixRef& P0, double tolerance, int max_iterations) {
  care::check_inputs(A, B, Q, R);
  NewtonKleinmanSolver solver(Q, R, tolerance, max_iterations);
  try {
    return solver.solve(A, B, P0);
  } catch (const Error& error) {
    rethrow_with_diagnosis(error, A, B, Q);
  }
}

}  // namespace thetad
