#include "core/lyapunov_certificate.hpp"

#include <limits>

namespace thetad {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

}  // namespace

LyapunovCertificate::LyapunovCertificate(Eigen::Index n) : M_(n, n), cholesky_(n) {}

bool LyapunovCertificate::positive_definite(const Eigen::MatrixXd& X, double rounding) {
  // A Cholesky factorization that succeeds in floating point is the exact one of X + E with
  // |E| ≤ γ_{n+1}|L||L'| (Higham, Accuracy and Stability of Numerical Algorithms, Thm 10.3), and
  // ‖ |L||L'| ‖_F ≤ n‖X + E‖_F: 2n(n+1)ε‖X‖_F bounds ‖E‖_2 with room for the second-order terms.
  const double n = static_cast<double>(X.rows());
  const double margin = rounding + 2.0 * n * (n + 1.0) * kEps * X.norm();
  cholesky_.compute(X - margin * Eigen::MatrixXd::Identity(X.rows(), X.cols()));
  return cholesky_.info() == Eigen::Success;
}

bool LyapunovCertificate::proves_hurwitz(const care::MatrixRef& A, const care::Weights& w, const Eigen::MatrixXd& P,
                                         const Eigen::MatrixXd& WP, const Eigen::MatrixXd& Res) {
  if (!positive_definite(P, 0.0)) return false;
  M_ = w.Q - Res;
  M_.noalias() += WP.transpose() * WP;
  // What Res and M carry of rounding, with their products bounded by the norms of their factors
  // (a product of inner dimension k errs by at most kε|X||Y| per entry, Higham Thm 3.5): not by
  // the size of the terms, which cancel and would understate it. Res = A'P + PA − (WP)'(WP) + Q,
  // and M adds Q and (WP)'(WP) once more.
  const double n = static_cast<double>(P.rows());
  const double m = static_cast<double>(WP.rows());
  const double wp_squared = WP.squaredNorm();
  const double rounding = (n + m + 4.0) * kEps * (w.Q.norm() + 2.0 * A.norm() * P.norm() + 2.0 * wp_squared);
  return positive_definite(M_, rounding);
}

}  // namespace thetad
