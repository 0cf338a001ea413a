// CareSolver's improvements of a direct solution and its error estimates (docs/care-estimates.md):
// the double-precision Newton refinement, the compensated steps, forward_error and condition.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/care_diagnosis.hpp"
#include "core/care_solver_workspace.hpp"
#include "core/error.hpp"
#include "core/machine_epsilon.hpp"

namespace thetad {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using care::Candidate;
using care::kRefineAbove;
using care::MatrixRef;

// The compensated Newton steps are considered when the terms A'P, PA and PGP exceed Q by more than
// this, i.e. when the residual of the exact solution rounded to double precision, about eps times
// that ratio relative to Q, is above 1e-10. Measured (docs/performance-log.md, 2026-11-27): the ratio
// is 8e3 … 1.4e6 with Q = I, R = I from n = 10 to 60, where the sign function is within issue 34's
// bound already, and 1e6 … 1e18 with the paper's weight spread (2.7e8 on the paper's own problem),
// where it was up to 1.3e4 times that bound without the steps.
constexpr double kTermsOverQ = 1e6;

}  // namespace

// W·P, the residual and η = care::normwise_residual of c.P.
void CareSolver::Workspace::evaluate(const MatrixRef& A, Candidate& c) const {
  c.WP.noalias() = w.W * c.P;
  care::care_residual(A, w, c.P, c.WP, c.Res);
  c.eta = care::normwise_residual(care::frobenius_norm(c.Res), w.q_norm, care::frobenius_norm(A), g_norm,
                                  care::frobenius_norm(c.P));
}

// Returns the refinement steps taken; candidate is replaced only by better ones.
int CareSolver::Workspace::refine(const MatrixRef& A) {
  constexpr int kMaxRefinements = 4;
  int refinements = 0;
  while (candidate.eta > kRefineAbove && refinements < kMaxRefinements) {
    Ak = A;
    Ak.noalias() -= w.W.transpose() * candidate.WP;
    try {
      refinement.lyapunov().factor(Ak);
      refinement.lyapunov().solve(candidate.Res, delta);
    } catch (const Error&) {
      break;  // A − GP is not Hurwitz: finish() reports that with the eigenvalue
    }
    next.P = candidate.P + delta;
    for (Index j = 0; j < n; ++j)
      for (Index i = 0; i < j; ++i) next.P(i, j) = next.P(j, i) = 0.5 * (next.P(i, j) + next.P(j, i));
    evaluate(A, next);
    if (!(next.eta < candidate.eta)) break;
    std::swap(candidate, next);
    ++refinements;
  }
  return refinements;
}

// Whether the terms of the equation dwarf Q, so that a residual in double precision is mostly
// rounding and the direct solution's forward error can exceed SB02OD's (docs/riccati.md).
bool CareSolver::Workspace::terms_dwarf_q(const MatrixRef& A) const {
  const double p_norm = care::frobenius_norm(candidate.P);
  const double terms = 2.0 * care::frobenius_norm(A) * p_norm + g_norm * p_norm * p_norm;
  return !(terms <= kTermsOverQ * w.q_norm);
}

// Newton steps with the residual in compensated arithmetic (care_refinement.hpp), all with the
// Schur form of the first closed loop (chord steps). None when that residual is within what
// forming Ω(P) = Ac'P + PAc in double precision leaves in the closed loop's balanced coordinates,
// two inner products of length n: balanced_residual_ratio ≤ 2nε. Measured (docs/performance-log.md,
// 2026-11-27): 8e-17 on the paper's problem and 4e-17 … 3.3e-15 on the SDRE's cold solves along
// scenario I, whose direct solutions the first correction puts 2e-16 … 7e-15 off, and 1.4e-14 … 7e-9 on
// every spread problem of the study whose direct solution missed issue 34's bound (the two below
// 2nε, at 6e-16 and 2.3e-15, met it). Each step's successor correction is the
// estimate of its P's error; the P with the smallest is kept, provided it stays backward stable.
// Usually the second correction is at rounding level and ends it; on one badly scaled problem the
// first step multiplied the error by 16 (the second-order term, not rounding) and the second
// brought it to 9e-15. known_forward_error then holds the estimate for the P kept. Returns the
// steps that led to it (0: P unchanged).
int CareSolver::Workspace::compensated_steps(const MatrixRef& A, const MatrixRef& B) {
  constexpr int kMaxSteps = 3;
  refinement.compute_residual(A, B, R, w, candidate.P);
  if (!refinement.residual().allFinite() || !refinement.balance_closed_loop(A, B)) return 0;
  closed_loop_balanced = true;
  if (!(refinement.balanced_residual_ratio(candidate.P) > 2.0 * static_cast<double>(n) * kEps)) return 0;
  if (!refinement.factor_closed_loop()) return 0;
  closed_loop_factored = true;
  if (!refinement.correction(delta)) return 0;
  double best = care::frobenius_norm(delta);
  known_forward_error = best / care::frobenius_norm(candidate.P);
  const double eta_bound = std::max(candidate.eta, kRefineAbove);
  double previous = best;
  int kept = 0;
  next.P = candidate.P;
  for (int step = 0; step < kMaxSteps; ++step) {
    next.P += delta;
    for (Index j = 0; j < n; ++j)
      for (Index i = 0; i < j; ++i) next.P(i, j) = next.P(j, i) = 0.5 * (next.P(i, j) + next.P(j, i));
    evaluate(A, next);
    if (!(next.eta <= eta_bound)) break;
    refinement.compute_residual(A, B, R, w, next.P);
    if (!refinement.residual().allFinite() || !refinement.correction(delta)) break;
    const double size = care::frobenius_norm(delta);
    const double p_norm = care::frobenius_norm(next.P);
    if (size < best) {
      candidate = next;
      best = size;
      known_forward_error = size / p_norm;
      kept = step + 1;
    }
    if (size <= kEps * p_norm || size > 10.0 * previous) break;
    previous = size;
  }
  return kept;
}

// CareResult::forward_error and condition for candidate.P (docs/care-estimates.md): the Newton
// correction from the compensated residual is −(P − P_exact) to first order. The closed loop of a
// compensated step's starting point serves: it differs from P's by that step, a second-order
// change in the estimate.
void CareSolver::Workspace::estimate_errors(const MatrixRef& A, const MatrixRef& B) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  result.forward_error = result.condition = nan;
  if (std::isnan(known_forward_error)) {
    // When compensated_steps stopped before a correction, refinement holds candidate.P's residual
    // and balanced closed loop.
    if (!closed_loop_balanced) {
      refinement.compute_residual(A, B, R, w, candidate.P);
      if (!refinement.residual().allFinite() || !refinement.balance_closed_loop(A, B)) return;
      closed_loop_balanced = true;
    }
    if (!closed_loop_factored) {
      if (!refinement.factor_closed_loop()) return;
      closed_loop_factored = true;
    }
    if (!refinement.correction(delta, true)) return;
    const double p_norm = care::frobenius_norm(candidate.P);
    const double delta_norm = care::frobenius_norm(delta);
    known_forward_error = p_norm > 0.0 ? delta_norm / p_norm : (delta_norm == 0.0 ? 0.0 : nan);
  }
  const double p_norm = care::frobenius_norm(candidate.P);
  const double terms = w.q_norm + 2.0 * care::frobenius_norm(A) * p_norm + g_norm * p_norm * p_norm;
  result.forward_error = known_forward_error;
  result.condition = p_norm > 0.0 ? refinement.lyapunov_inverse_norm() * terms / p_norm : nan;
}

}  // namespace thetad
