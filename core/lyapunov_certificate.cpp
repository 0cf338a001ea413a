#include "core/lyapunov_certificate.hpp"

#include <cmath>

#include "core/machine_epsilon.hpp"

namespace thetad {

LyapunovCertificate::LyapunovCertificate(Eigen::Index n) : M_(n, n), cholesky_(n) {}

bool LyapunovCertificate::positive_definite(const Eigen::MatrixXd& X, double rounding) {
  // A Cholesky factorization that succeeds in floating point is the exact one of X − mI + E with
  // |E| ≤ γ_{n+1}|L||L'| (Higham, Accuracy and Stability of Numerical Algorithms, Thm 10.3), and
  // ‖ |L||L'| ‖_F ≤ ‖L‖_F² = tr(X − mI + E) ≤ √n‖X‖_F + n‖E‖_2, so ‖E‖_2 ≲ (n + 1)√n ε‖X‖_F:
  // 2n(n + 1)ε‖X‖_F bounds it with room for the second-order terms.
  const double n = static_cast<double>(X.rows());
  const double margin = rounding + 2.0 * n * (n + 1.0) * kEps * care::frobenius_norm(X);
  // A NaN or an infinity would pass: LLT fails only on a pivot ≤ 0, and NaN ≤ 0 is false.
  if (!std::isfinite(margin)) return false;
  cholesky_.compute(X - margin * Eigen::MatrixXd::Identity(X.rows(), X.cols()));
  return cholesky_.info() == Eigen::Success;
}

bool LyapunovCertificate::proves_hurwitz(const care::MatrixRef& A, const care::Weights& w, const Eigen::MatrixXd& P,
                                         const Eigen::MatrixXd& WP, const Eigen::MatrixXd& Res) {
  if (!positive_definite(P, 0.0)) return false;
  M_ = w.Q - Res;
  M_.noalias() += WP.transpose() * WP;
  // What M carries of rounding, with every product bounded by the norms of its factors (a product
  // of inner dimension k errs by at most kε|X||Y| per entry, Higham Thm 3.5), not by the size of
  // the terms, which cancel and would understate it: Res = A'P + PA − (WP)'(WP) + Q, M adds Q and
  // (WP)'(WP) once more, and WP itself is W·P rounded, which enters M twice against WP (the closed
  // loop proved Hurwitz is A − W'W P with the exact product).
  const double n = static_cast<double>(P.rows());
  const double m = static_cast<double>(WP.rows());
  const double wp_norm = care::frobenius_norm(WP);
  const double p_norm = care::frobenius_norm(P);
  const double terms = w.q_norm + 2.0 * care::frobenius_norm(A) * p_norm + 2.0 * wp_norm * wp_norm;
  const double rounding =
      (n + m + 4.0) * kEps * terms + 4.0 * n * kEps * care::frobenius_norm(w.W) * p_norm * wp_norm;
  return positive_definite(M_, rounding);
}

}  // namespace thetad
