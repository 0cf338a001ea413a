#pragma once

// Continuous-time Lyapunov equations  A'X + XA + Q = 0.
//
// Two entry points, for two situations:
//  - solve_lyapunov: a one-off equation with any A (Bartels–Stewart on the real Schur form).
//  - ConstantLyapunovSolver: many equations that share one Hurwitz coefficient matrix, as the
//    θ–D recursion does (docs/model.md §8.1: every T_i, i ≥ 1, solves L(T) = T Ac0 + Ac0' T
//    = e_i W_i with the same constant Ac0). Everything that depends on Ac alone is paid once at
//    construction; a solve is then one dense matrix–vector product and allocates nothing.
//    docs/riccati.md has the measurements behind this choice.

#include <Eigen/Dense>

namespace thetad {

// Returns X with A'X + XA + Q = 0 (A n×n, Q n×n; Q need not be symmetric, but if it is, X is
// returned exactly symmetric). Bartels–Stewart: real Schur form of A, then a sweep over the
// quasi-triangular equation (LyapunovWorkspace).
// Throws thetad::Error on dimension mismatch, non-finite entries, and when the Lyapunov operator
// is singular to working precision: min |λi(A) + λj(A)| ≤ 1e-10·max(‖A‖_F, 1), i.e. A and −A
// share an eigenvalue (e.g. A has eigenvalues ±1, or any eigenvalue on the imaginary axis).
Eigen::MatrixXd solve_lyapunov(const Eigen::Ref<const Eigen::MatrixXd>& A,
                               const Eigen::Ref<const Eigen::MatrixXd>& Q);

// solve_lyapunov for a new A at every call of a hot path (Newton–Kleinman inside a control step):
// every buffer is sized once, at construction, for one n, and neither phase allocates. Two phases,
// because a caller often wants A's spectrum before it solves, and solves several equations with
// one A: the Schur form of A gives the spectrum for free and serves every solve.
//
// The Schur form is Eigen's RealSchur and the quasi-triangular equation T'Y + YT = C is solved by
// a block sweep written here, which visits only the lower half when C is symmetric: measured in
// bench/riccati_bench.cpp against LAPACK dgees + dtrsyl (the reference LAPACK of Debian), on the
// closed loops of the paper's problem (docs/riccati.md).
class LyapunovWorkspace {
 public:
  explicit LyapunovWorkspace(Eigen::Index n);

  // Real Schur form A = U T U' and the eigenvalues of A. Throws thetad::Error on a size mismatch,
  // non-finite entries or when the QR iteration does not converge.
  void factor(const Eigen::Ref<const Eigen::MatrixXd>& A);
  // Eigenvalues of the last factor()ed A, in Schur order.
  const Eigen::VectorXd& eigenvalues_real() const { return wr_; }
  const Eigen::VectorXd& eigenvalues_imag() const { return wi_; }
  double max_real_eigenvalue() const { return wr_.maxCoeff(); }

  // X with A'X + XA + Q = 0 for the A of the last factor(); Q symmetric gives X exactly
  // symmetric. Throws as solve_lyapunov, unless refuse_singular is false: then a Lyapunov operator
  // singular to working precision gives the huge X it implies, for a caller that wants to see how
  // huge (the CARE error estimates of care_refinement.hpp).
  void solve(const Eigen::Ref<const Eigen::MatrixXd>& Q, Eigen::Ref<Eigen::MatrixXd> X, bool refuse_singular = true);

 private:
  // T'Y + YT = Y in place, T = schur_.matrixT().
  void sweep(bool symmetric);

  Eigen::Index n_;
  Eigen::RealSchur<Eigen::MatrixXd> schur_;  // A = U T U'
  // From n = 48 on, where RealSchur would form U with blocked Householder products (they
  // allocate), the Hessenberg form and U come from these, the reflectors applied in place.
  Eigen::HessenbergDecomposition<Eigen::MatrixXd> hessenberg_;
  Eigen::MatrixXd hessenberg_q_;
  Eigen::VectorXd householder_workspace_;
  Eigen::MatrixXd Y_, scratch_;  // U'XU, and the one intermediate of a triple product
  Eigen::VectorXd wr_, wi_;
  double a_norm_ = 0.0;
  bool factored_ = false;
};

// Solves Ac'X + XAc + Q = 0 for many symmetric Q with one fixed Hurwitz Ac.
//
// Method: because Q (hence X) is symmetric, only the n(n+1)/2 unknowns x_ij, i ≤ j, are needed;
// the Lyapunov operator restricted to them is a dense n(n+1)/2-square matrix (171×171 at n = 18)
// that is inverted once here. solve() packs the upper triangle of Q, multiplies by the stored
// inverse and unpacks: ~n⁴/4 flops, no branches, no allocation.
// The construction cost is O(n⁶) (an LU of the packed operator): fine up to n ≈ 60.
//
// Not thread-safe per object: solve() uses buffers owned by the object. Use one solver per
// thread (they are cheap to copy).
class ConstantLyapunovSolver {
 public:
  // Throws thetad::Error if Ac is not square, not finite, not Hurwitz (the message gives the
  // largest real part of its eigenvalues), or if the packed operator is singular to working
  // precision (condition number above 1e14).
  explicit ConstantLyapunovSolver(const Eigen::Ref<const Eigen::MatrixXd>& Ac);

  // Hot path. Q must be symmetric (only its upper triangle is read; debug builds check the
  // symmetry); X must already be n×n; X is written completely and is exactly symmetric.
  // Throws thetad::Error on a size mismatch; allocates nothing otherwise.
  void solve(const Eigen::Ref<const Eigen::MatrixXd>& Q, Eigen::Ref<Eigen::MatrixXd> X) const;

  // Convenience for cold paths: allocates the result.
  Eigen::MatrixXd solve(const Eigen::Ref<const Eigen::MatrixXd>& Q) const;

  Eigen::Index size() const { return n_; }
  // 1-norm condition number of the packed n(n+1)/2-square operator (exact: the inverse is
  // stored). The relative error of a solve is at most about this times machine epsilon.
  double condition_number() const { return condition_number_; }
  // Largest real part of the eigenvalues of Ac (negative: Ac is Hurwitz).
  double max_real_eigenvalue() const { return max_real_eigenvalue_; }

  // The packed operator itself, for callers that solve only some unknowns or precompute the
  // solutions of fixed right sides (θ–D, docs/riccati.md): x = packed_inverse() * q, with q
  // and x the upper triangles in packed_index order, solves Ac'X + XAc + Q = 0.
  const Eigen::MatrixXd& packed_inverse() const { return inverse_; }
  // Position of x_ij (i ≤ j) in the packed vector: upper triangle, column by column, as LAPACK's
  // packed storage, so that packing and unpacking walk Q and X in memory order.
  static Eigen::Index packed_index(Eigen::Index i, Eigen::Index j) { return j * (j + 1) / 2 + i; }

 private:
  Eigen::Index n_;
  // Minus the inverse of the packed operator, so that x_packed = inverse_ * q_packed.
  Eigen::MatrixXd inverse_;
  double condition_number_;
  double max_real_eigenvalue_;
  mutable Eigen::VectorXd q_packed_;
  mutable Eigen::VectorXd x_packed_;
};

}  // namespace thetad
