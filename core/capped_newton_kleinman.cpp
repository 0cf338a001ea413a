#include "core/capped_newton_kleinman.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace thetad {

using MatrixRef = Eigen::Ref<const Eigen::MatrixXd>;

CappedNewtonKleinman::CappedNewtonKleinman(const MatrixRef& Q, const MatrixRef& R, int steps)
    : R_(R), steps_(steps), lyapunov_(std::max<Eigen::Index>(Q.rows(), 1)) {
  const Eigen::Index n = Q.rows(), m = R.rows();
  if (n == 0 || Q.cols() != n) care::fail("Q must be square and non-empty, but Q is " + care::shape(Q));
  if (m == 0 || R.cols() != m) care::fail("R must be square and non-empty, but R is " + care::shape(R));
  if (!Q.allFinite()) care::fail("Q has a non-finite entry (NaN or Inf)");
  if (!R.allFinite()) care::fail("R has a non-finite entry (NaN or Inf)");
  if (steps < 1) care::fail("capped Newton–Kleinman needs at least one step, got " + std::to_string(steps));
  weights_ = care::prepare_weights(Q, R);
  weights_.W.resize(m, n);
  P_.resize(n, n);
  WP_.resize(m, n);
  Res_.resize(n, n);
  closed_loop_.resize(n, n);
  delta_.resize(n, n);
  WPWPt_.resize(m, m);
}

double CappedNewtonKleinman::evaluate(const MatrixRef& A) {
  WP_.noalias() = weights_.W * P_;
  const double AtP_norm = care::care_residual(A, weights_, P_, WP_, Res_);
  WPWPt_.noalias() = WP_ * WP_.transpose();  // ‖PGP‖_F = ‖(WP)(WP)'‖_F, m×m
  return care::residual_to_terms(care::frobenius_norm(Res_), weights_.q_norm, AtP_norm, care::frobenius_norm(WPWPt_));
}

const Eigen::MatrixXd& CappedNewtonKleinman::solve(const MatrixRef& A, const MatrixRef& B, const MatrixRef& P0) {
  care::check_inputs(A, B, weights_.Q, R_);
  if (P0.rows() != P_.rows() || P0.cols() != P_.cols())
    care::fail("P0 is " + care::shape(P0) + " but A is " + care::shape(A));
  if (!P0.allFinite()) care::fail("P0 has a non-finite entry (NaN or Inf)");
  care::set_input_matrix(weights_, B);
  P_ = P0;
  care::symmetrize(P_);
  double rho = evaluate(A);
  for (int step = 1; step <= steps_; ++step) {
    closed_loop_ = A;
    closed_loop_.noalias() -= weights_.W.transpose() * WP_;
    try {
      lyapunov_.factor(closed_loop_);
    } catch (const Error& e) {
      care::fail("capped Newton–Kleinman step " + std::to_string(step) + ": " + e.what());
    }
    // Kleinman: every closed loop is Hurwitz when P0's is; checked because P0 is the last
    // sample's P, not this sample's, and the Schur form gives the spectrum for free.
    const double max_real = lyapunov_.max_real_eigenvalue();
    if (!(max_real < 0.0))
      care::fail("capped Newton–Kleinman: A − G P is not Hurwitz before step " + std::to_string(step) +
                 " (largest Re λ " + care::num(max_real) + ")");
    try {
      lyapunov_.solve(Res_, delta_);
    } catch (const Error& e) {
      care::fail("capped Newton–Kleinman step " + std::to_string(step) + ": " + e.what());
    }
    P_ += delta_;
    care::symmetrize(P_);
    rho = evaluate(A);
  }
  if (!std::isfinite(rho)) care::fail("capped Newton–Kleinman: the residual is not finite after the last step");
  rho_ = rho;
  return P_;
}

}  // namespace thetad
