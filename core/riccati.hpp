#pragma once

// Continuous-time algebraic Riccati equation (CARE)
//
//     A'P + PA − P B R⁻¹ B' P + Q = 0,
//
// solved for the stabilizing solution P (all eigenvalues of A − B R⁻¹B'P in the open left
// half-plane). It exists and is unique, symmetric and positive semi-definite when R is
// positive definite, Q is positive semi-definite, (A, B) is stabilizable and (Q, A) has no
// unobservable mode on the imaginary axis (detectability suffices). Controllability is not
// required: a stable uncontrollable mode (the s-mode of the helicopter plant) is fine.
//
// Both solvers throw thetad::Error, never return a wrong P, when:
//  - a dimension does not match (the message names the matrix and both sizes);
//  - an entry is not finite;
//  - Q is not symmetric or not positive semi-definite (the message gives min eig Q);
//  - R is not symmetric positive definite;
//  - the Hamiltonian has eigenvalues on (numerically at) the imaginary axis, or there is no
//    stabilizing solution (too few stable eigenvalues, or the stable-subspace basis block U1
//    singular to working precision: the message gives rcond(U1));
//  - the closed-loop matrix A − BK that comes out is not Hurwitz.
// The error reporting follows SLICOT SB02MD / MATLAB care.

#include <Eigen/Dense>

namespace thetad {

struct CareResult {
  Eigen::MatrixXd P;                         // stabilizing solution, exactly symmetric
  Eigen::MatrixXd K;                         // R⁻¹ B' P: the optimal feedback is u = −K x
  Eigen::VectorXcd closed_loop_eigenvalues;  // eig(A − B K)
  // ‖A'P + PA − PBR⁻¹B'P + Q‖_F / max(1, ‖Q‖_F). On ill-conditioned equations the terms of
  // the sum can be far larger than Q, and so is this number even for a backward-stable solve.
  double relative_residual;
  // Newton steps taken. solve_care: Newton refinement steps after the Schur solution, 0 unless
  // that solution was not backward stable (see riccati.cpp).
  int iterations;
};

// Laub's Schur method: the ordered real Schur form of the (scaled) Hamiltonian
// H = [A, −G; −Q, −A'], G = B R⁻¹ B', gives a basis [U1; U2] of its stable invariant subspace
// and P = U2 U1⁻¹.
CareResult solve_care(const Eigen::Ref<const Eigen::MatrixXd>& A,
                      const Eigen::Ref<const Eigen::MatrixXd>& B,
                      const Eigen::Ref<const Eigen::MatrixXd>& Q,
                      const Eigen::Ref<const Eigen::MatrixXd>& R);

// Newton–Kleinman from the warm start P0, which must be stabilizing (A − G P0 Hurwitz): each
// step solves the Lyapunov equation (A − G Pk)'X + X(A − G Pk) + Q + Pk G Pk = 0 for Pk+1 = X.
// Stops when the step ‖Pk+1 − Pk‖_F ≤ tolerance·max(1, ‖Pk+1‖_F) or the relative residual is
// ≤ tolerance; throws if that does not happen within max_iterations steps.
CareResult solve_care_newton(const Eigen::Ref<const Eigen::MatrixXd>& A,
                             const Eigen::Ref<const Eigen::MatrixXd>& B,
                             const Eigen::Ref<const Eigen::MatrixXd>& Q,
                             const Eigen::Ref<const Eigen::MatrixXd>& R,
                             const Eigen::Ref<const Eigen::MatrixXd>& P0,
                             double tolerance = 1e-12, int max_iterations = 50);

}  // namespace thetad
