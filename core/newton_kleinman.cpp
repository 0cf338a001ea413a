#include "core/newton_kleinman.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/care_diagnosis.hpp"
#include "core/error.hpp"

namespace thetad {
namespace {

using care::fail;
using care::num;
using Eigen::Index;
using Eigen::MatrixXd;
using MatrixRef = Eigen::Ref<const MatrixXd>;

// The steps add a Δ that is symmetric only up to rounding (the residual's GEMMs need not be): P
// stays exactly symmetric by averaging the pairs in place.
void symmetrize(MatrixXd& P) {
  for (Index j = 0; j < P.cols(); ++j)
    for (Index i = 0; i < j; ++i) P(i, j) = P(j, i) = 0.5 * (P(i, j) + P(j, i));
}

// ρ = ‖Res‖_F / (‖Q‖_F + 2‖A'P‖_F + ‖PGP‖_F): the residual against the terms that cancel in it.
// Not solve_care's normwise η (‖A‖‖P‖ and ‖G‖‖P‖² in place of the terms): on the paper's
// problem P is large where G is small, ‖G‖‖P‖² overstates ‖PGP‖ by ten orders of magnitude and η
// is 1e-25 for a P off by 1e-3 (measured), while ρ of the rounded exact solution is ~1e-16.
double relative_to_terms(double residual_norm, double q_norm, double AtP_norm, double PGP_norm) {
  return residual_norm / (q_norm + 2.0 * AtP_norm + PGP_norm);
}

}  // namespace

NewtonKleinmanSolver::NewtonKleinmanSolver(const MatrixRef& Q, const MatrixRef& R, double tolerance,
                                           int max_iterations)
    : R_(R), tolerance_(tolerance), max_iterations_(max_iterations), n_(Q.rows()), m_(R.rows()),
      lyapunov_(std::max<Index>(Q.rows(), 1)) {
  if (n_ == 0 || Q.cols() != n_) fail("Q must be square and non-empty, but Q is " + care::shape(Q));
  if (m_ == 0 || R.cols() != m_) fail("R must be square and non-empty, but R is " + care::shape(R));
  if (!Q.allFinite()) fail("Q has a non-finite entry (NaN or Inf)");
  if (!R.allFinite()) fail("R has a non-finite entry (NaN or Inf)");
  if (!(tolerance > 0.0) || max_iterations < 1)
    fail("Newton–Kleinman needs tolerance > 0 and max_iterations ≥ 1 (got " + num(tolerance) + ", " +
         std::to_string(max_iterations) + ")");
  weights_ = care::prepare_weights(Q, R);
  q_norm_ = weights_.Q.norm();
  weights_.W.resize(m_, n_);
  P_.resize(n_, n_);
  WP_.resize(m_, n_);
  Res_.resize(n_, n_);
  Ak_.resize(n_, n_);
  delta_.resize(n_, n_);
  WPWPt_.resize(m_, m_);
  result_.P.resize(n_, n_);
  result_.K.resize(m_, n_);
  result_.closed_loop_eigenvalues.resize(n_);
}

double NewtonKleinmanSolver::evaluate(const MatrixRef& A) {
  WP_.noalias() = weights_.W * P_;
  const double AtP_norm = care::care_residual(A, weights_, P_, WP_, Res_);
  WPWPt_.noalias() = WP_ * WP_.transpose();  // ‖PGP‖_F = ‖(WP)'(WP)‖_F = ‖(WP)(WP)'‖_F, m×m
  return relative_to_terms(Res_.norm(), q_norm_, AtP_norm, WPWPt_.norm());
}

const CareResult& NewtonKleinmanSolver::solve(const MatrixRef& A, const MatrixRef& B, const MatrixRef& P0) {
  care::check_inputs(A, B, weights_.Q, R_);
  if (P0.rows() != n_ || P0.cols() != n_) fail("P0 is " + care::shape(P0) + " but A is " + care::shape(A));
  if (!P0.allFinite()) fail("P0 has a non-finite entry (NaN or Inf)");
  care::set_input_matrix(weights_, B);

  P_ = P0;
  symmetrize(P_);
  double rho = evaluate(A);
  double previous_rho = std::numeric_limits<double>::infinity();
  double step = std::numeric_limits<double>::infinity();
  double previous_step = std::numeric_limits<double>::infinity();
  int iterations = 0;
  for (;;) {
    if (!std::isfinite(rho)) fail("Newton–Kleinman: the residual is not finite at step " + std::to_string(iterations));
    // At least one step: a residual is blind to some errors of P (ill-conditioned directions), the
    // Newton step measures them. Then stop on the returned P's own ρ once the step is within the
    // tolerance or has stopped shrinking, i.e. reached the rounding level of this equation.
    if (iterations > 0) {
      const bool settled = step <= tolerance_ * std::max(1.0, P_.norm()) || step > 0.5 * previous_step;
      if (rho <= tolerance_ && settled) break;
      if (settled && !(rho < previous_rho))
        fail("Newton–Kleinman stalled above the tolerance: the residual ρ went from " + num(previous_rho) +
             " to " + num(rho) + " at step " + std::to_string(iterations) + " (tolerance " + num(tolerance_) + ")");
    }
    if (iterations == max_iterations_)
      fail("Newton–Kleinman did not converge in " + std::to_string(iterations) + " iterations (residual ρ " +
           num(rho) + ", last relative step " + num(step / std::max(1.0, P_.norm())) + ", tolerance " +
           num(tolerance_) + ")");
    Ak_ = A;
    Ak_.noalias() -= weights_.W.transpose() * WP_;
    try {
      lyapunov_.factor(Ak_);
    } catch (const Error& e) {
      fail("Newton–Kleinman step " + std::to_string(iterations + 1) + ": " + e.what());
    }
    // The closed loop of Pk is stable for every k when P0 stabilizes (Kleinman): its Schur form,
    // needed for the step anyway, checks P0 and guards against rounding later.
    const double max_real = lyapunov_.max_real_eigenvalue();
    if (!(max_real < 0.0))
      fail(iterations == 0 ? "Newton–Kleinman: P0 is not stabilizing (largest Re λ of A − G P0 is " + num(max_real) + ")"
                           : "Newton–Kleinman: A − G P lost stability at step " + std::to_string(iterations) +
                                 " (largest Re λ " + num(max_real) + ")");
    try {
      lyapunov_.solve(Res_, delta_);
    } catch (const Error& e) {
      fail("Newton–Kleinman step " + std::to_string(iterations + 1) + ": " + e.what());
    }
    P_ += delta_;
    symmetrize(P_);
    ++iterations;
    previous_step = step;
    step = delta_.norm();
    previous_rho = rho;
    rho = evaluate(A);
  }

  // The one spectrum of the call: the closed loop of the P returned.
  Ak_ = A;
  Ak_.noalias() -= weights_.W.transpose() * WP_;
  lyapunov_.compute_eigenvalues(Ak_);
  const double max_real = lyapunov_.max_real_eigenvalue();
  if (!(max_real < 0.0))
    fail("the solution is not stabilizing: A − BK has an eigenvalue with Re λ = " + num(max_real) +
         care::kStabilizabilityHint);
  rho_ = rho;
  result_.P = P_;
  result_.K = WP_;
  weights_.L.transpose().triangularView<Eigen::Upper>().solveInPlace(result_.K);
  for (Index i = 0; i < n_; ++i)
    result_.closed_loop_eigenvalues(i) = {lyapunov_.eigenvalues_real()(i), lyapunov_.eigenvalues_imag()(i)};
  result_.relative_residual = Res_.norm() / std::max(1.0, q_norm_);
  result_.iterations = iterations;
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
