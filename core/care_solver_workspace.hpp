#pragma once

// CareSolver's workspace (core/riccati.hpp), shared by the files that implement it: riccati.cpp
// (the direct solutions and the result) and care_solver_refinement.cpp (the Newton refinements
// and the error estimates). Internal: not part of the installed interface's promises.

#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/care_refinement.hpp"
#include "core/care_weights.hpp"
#include "core/lyapunov_certificate.hpp"
#include "core/matrix_sign.hpp"
#include "core/riccati.hpp"

namespace thetad {

namespace care {

// Newton refinement only when a direct solution is not backward stable. Measured: η is at
// rounding level on the helicopter plant, CAREX 1.x–4.1 and random systems, and one Newton step
// there gains nothing and can cost forward accuracy (CAREX 2.4: 3e-11 → 1.4e-9 relative error);
// on the badly scaled CAREX 2.6, η = 2.4e-4 after the Schur method and two steps bring the error
// from 9e-4 to 1e-12.
inline constexpr double kRefineAbove = 1e-12;

// A P with everything finish() and the refinement need about it.
struct Candidate {
  Eigen::MatrixXd P;  // symmetric
  Eigen::MatrixXd WP;
  Eigen::MatrixXd Res;
  double eta = 0.0;  // normwise backward error, see evaluate()
};

}  // namespace care

// Both direct methods work on a diagonally scaled H_s = D⁻¹ H D, D = diag(d); a basis of the
// stable subspace of H is D times one of H_s's, so [I; P_s] for H_s gives P = D2 P_s D1⁻¹.
struct CareSolver::Workspace {
  Workspace(const care::MatrixRef& Q, const care::MatrixRef& R, CareMethod method, StabilityProof proof, ErrorEstimates estimates);

  const CareResult& solve(const care::MatrixRef& A, const care::MatrixRef& B);

  void form_hamiltonian(const care::MatrixRef& A);
  void scale_hamiltonian();
  void equilibrate();
  void balance();
  bool sign_solution(int& iterations);
  void schur_solution();
  void unscale(const Eigen::Ref<const Eigen::MatrixXd>& P_s, Eigen::MatrixXd& P) const;
  void evaluate(const care::MatrixRef& A, care::Candidate& c) const;
  int refine(const care::MatrixRef& A);
  bool terms_dwarf_q(const care::MatrixRef& A) const;
  int compensated_steps(const care::MatrixRef& A, const care::MatrixRef& B);
  void estimate_errors(const care::MatrixRef& A, const care::MatrixRef& B);
  const CareResult& finish(const care::MatrixRef& A, const care::MatrixRef& B, bool have_spectrum, int iterations);

  CareMethod method;
  StabilityProof proof;
  ErrorEstimates estimates;
  care::Weights w;
  Eigen::MatrixXd R;  // as given: for check_inputs' sizes and the compensated residual (Kleinman's form)
  Eigen::Index n, m;
  double g_norm = 0.0;
  Eigen::MatrixXd H, H_s;  // H = [A, −G; −Q, −A'] and D⁻¹ H D
  Eigen::VectorXd d, d_balance;
  MatrixSignSolver sign;
  Eigen::MatrixXd lhs, rhs;  // [S12; S22 + I] and −[S11 + I; S21]
  Eigen::VectorXd qr_coefficients, qr_workspace;
  Eigen::MatrixXd U, U1, X;  // Schur vectors of H_s, U1 factored, U2' solved into X
  Eigen::VectorXd wr, wi, schur_work, lu_work;
  std::vector<int> bwork, pivots, lu_iwork;
  care::Candidate candidate, next;
  Eigen::MatrixXd Ak, delta;
  CareRefinement refinement;  // its LyapunovWorkspace also serves refine()
  // What refinement holds for this solve: A − BK balanced, and its Schur form.
  bool closed_loop_balanced = false;
  bool closed_loop_factored = false;
  // The forward-error estimate of candidate.P once compensated_steps has one; NaN before.
  double known_forward_error = std::numeric_limits<double>::quiet_NaN();
  LyapunovCertificate certificate;
  Eigen::EigenSolver<Eigen::MatrixXd> eigen;
  CareResult result;
};

}  // namespace thetad
