#pragma once

// The Newton correction of a computed CARE solution with its residual taken in compensated
// arithmetic, and the error estimates built on it (docs/care-estimates.md derives them).
//
// On problems whose weights span decades the terms A'P, PA and PGP are 1e6 … 1e18 times larger
// than Q and cancel, so a residual computed in double precision is mostly rounding, and a Newton
// step driven by it moves P as much away from the solution as towards it (docs/performance-log.md).
// Here the residual is exact to about eps² of the terms: every product is an error-free
// transformation (Dekker's two-product) summed with Knuth's two-sum (the Dot2 of Ogita, Rump and
// Oishi 2005), and G = BR⁻¹B' is never formed. Kleinman's form does that: with M = B'P and any K,
//   A'P + PA + Q − M'K − K'M + K'RK = Res(P) + (K − R⁻¹M)'R(K − R⁻¹M),
// so K = R⁻¹M from R's Cholesky factor in double precision errs only in second order.

#include <Eigen/Dense>

#include "core/care_weights.hpp"
#include "core/lyapunov.hpp"

namespace thetad {

// Every buffer is sized at construction for one n and m; nothing allocates after it unless the
// Lyapunov solver throws. Not thread-safe per object.
class CareRefinement {
 public:
  CareRefinement(Eigen::Index n, Eigen::Index m);

  // Res(P) = A'P + PA − PBR⁻¹B'P + Q into residual(), in compensated arithmetic (R = LL' given as
  // w.L, Q as w.Q). P must be symmetric.
  void compute_residual(const care::MatrixRef& A, const care::MatrixRef& B, const care::MatrixRef& R,
                        const care::Weights& w, const Eigen::MatrixXd& P);
  const Eigen::MatrixXd& residual() const { return residual_; }
  // The K = R⁻¹B'P of the last compute_residual (double precision).
  const Eigen::MatrixXd& gain() const { return K_; }

  // Ac = A − B·gain(), balanced: Ãc = D⁻¹AcD by LAPACK dgebal, scaling only (on badly scaled
  // states the unbalanced correction was larger than the error it was to remove). False when
  // dgebal fails.
  bool balance_closed_loop(const care::MatrixRef& A, const care::MatrixRef& B);
  // ‖D·residual()·D‖_F / (‖Ãc‖_F ‖DPD‖_F): the residual in the balanced coordinates against the size
  // of Ω(P̃) there, whose forming in double precision alone errs by up to about 2nε of it
  // (docs/care-estimates.md).
  double balanced_residual_ratio(const Eigen::MatrixXd& P) const;  // the P of compute_residual
  // The real Schur form of Ãc, for correction() and lyapunov_inverse_norm(). False (and nothing to
  // solve with) when Ac is not Hurwitz or its Schur form fails.
  bool factor_closed_loop();
  // Δ with Ac'Δ + ΔAc + residual() = 0, Ac as last factored: Newton's step for P, and to first
  // order −(P − P_exact). False when the solve fails or Δ is not finite. A Lyapunov operator
  // singular to working precision fails it, unless for an estimate (even_if_singular): then Δ is
  // as large as that makes it.
  bool correction(Eigen::MatrixXd& delta, bool even_if_singular = false);
  // ‖Ω⁻¹‖ for Ω(X) = Ac'X + XAc, as ‖H‖_F with Ac'H + HAc + I = 0: the norm induced by the
  // spectral norm is exactly ‖H‖₂ (−Ω⁻¹ is a positive map, which takes its norm at I), and
  // ‖H‖₂ ≤ ‖H‖_F ≤ √n ‖H‖₂. Large, not NaN, when Ω is singular to working precision.
  double lyapunov_inverse_norm();

  // The Lyapunov solver, lent to a caller whose own Newton steps (in double precision) come before
  // this object's: one workspace, not two, in every CareSolver. factor_closed_loop() again after.
  LyapunovWorkspace& lyapunov() { return lyapunov_; }

 private:
  // X with Ac'X + XAc + W = 0 through the balanced Schur form.
  bool solve_balanced(const Eigen::MatrixXd& W, Eigen::MatrixXd& X, bool even_if_singular);

  Eigen::Index n_, m_;
  LyapunovWorkspace lyapunov_;
  double sigma_ = 1.0;                // a power of two near 1/‖P‖ (compute_residual)
  Eigen::MatrixXd P_scaled_;          // σP
  Eigen::MatrixXd P_hi_, P_lo_;       // σP split in halves of 26 bits (Dekker)
  Eigen::MatrixXd Z_, Z_err_;         // PA, as sum and error: (A'P)' since P = P'
  Eigen::MatrixXd N_, N_err_;         // PB = (B'P)'
  Eigen::MatrixXd N_hi_, N_lo_;       // PB split
  Eigen::MatrixXd K_, E_;             // R⁻¹B'P, and RK − B'P
  Eigen::MatrixXd V_, V_err_;         // (PB)K = M'K
  Eigen::MatrixXd KE_;                // K'E, in double: E is at rounding level of M
  Eigen::MatrixXd residual_, Ac_, scaled_, identity_, H_;
  Eigen::VectorXd balance_;           // Ac is solved with as D⁻¹AcD, D = diag(balance_)
};

}  // namespace thetad
