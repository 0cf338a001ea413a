#pragma once

// A proof that the closed loop of a CARE iterate is Hurwitz, without computing its spectrum.
//
// With Ac = A − G P and Res = A'P + PA − PGP + Q for a symmetric P, Ac'P + PAc = Res − Q − PGP
// exactly. So when P ≻ 0 and Q + PGP − Res ≻ 0, x'Px is a Lyapunov function of ẋ = Ac x and Ac is
// Hurwitz (Lyapunov's theorem). Both are checked by Cholesky factorizations of the two matrices
// less a margin that covers the rounding of Res and of the factorizations themselves, so that a
// success proves the claim for the P at hand. A failure proves nothing: then only the spectrum can
// tell. It holds at the stabilizing solution whenever that is positive definite and Q + PGP is
// far enough from singular (Q ≻ 0 suffices); it cannot hold at any other solution of the CARE,
// whose closed loop is not Hurwitz. Its cost is two n×n Cholesky factorizations and an m×n×n
// product (riccati_bench's lyapunov_certificate row against lyapunov_factor_solve).
//
// The closed loop it speaks of is A − W'W P with the W of care::Weights, i.e. G = B R⁻¹B' as
// rounded in forming W = L⁻¹B', as the spectrum that NewtonKleinmanSolver computes otherwise.

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "core/care_weights.hpp"

namespace thetad {

class LyapunovCertificate {
 public:
  // Every buffer sized once: proves_hurwitz allocates nothing.
  explicit LyapunovCertificate(Eigen::Index n);

  // True when the inequalities above hold with their margins for A − W'W P, G = W'W of `w`
  // (care_weights.hpp). WP = W·P and Res = care::care_residual(A, w, P, WP, ·) of the same P;
  // P and Res are read on their lower triangle.
  bool proves_hurwitz(const care::MatrixRef& A, const care::Weights& w, const Eigen::MatrixXd& P,
                      const Eigen::MatrixXd& WP, const Eigen::MatrixXd& Res);

 private:
  // X − margin·I ≻ 0, X symmetric, known to within `rounding` in the 2-norm: the Cholesky
  // factorization of X − margin·I succeeds with margin = rounding plus the factorization's own
  // backward error bound.
  bool positive_definite(const Eigen::MatrixXd& X, double rounding);

  Eigen::MatrixXd M_;  // Q + PGP − Res
  Eigen::LLT<Eigen::MatrixXd> cholesky_;
};

}  // namespace thetad
