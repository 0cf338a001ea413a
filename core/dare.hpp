#pragma once

// Discrete-time algebraic Riccati equation (DARE) with a cross term S,
//
//     X = A'XA − (A'XB + S)(R + B'XB)⁻¹(B'XA + S') + Q,
//
// solved for the stabilizing solution X (all eigenvalues of A − BK, K = (R + B'XB)⁻¹(B'XA + S'),
// inside the unit circle): the Riccati equation of the discrete-time LQR with cost
// Σ x'Qx + u'Ru + 2x'Su. It exists and is unique when (A, B) is stabilizable, R and
// Q − SR⁻¹S' are positive (semi-)definite, and (Q − SR⁻¹S', A − BR⁻¹S') has no unobservable mode
// on the unit circle.
//
// solve_dare throws thetad::Error, never returns a wrong X, when:
//  - a dimension does not match or an entry is not finite (the message names the matrix);
//  - Q or R is not symmetric;
//  - R is singular to working precision (the doubling algorithm works on G = BR⁻¹B'; a DARE whose
//    R is singular but R + B'XB is not falls outside it);
//  - the doubling breaks down (I + G_k H_k singular) or does not converge within kDareDoublings:
//    the message names the broken precondition when the Popov–Belevitch–Hautus tests find one
//    ("the pair (A, B) is not stabilizable: ...", "(Q, A) is not detectable: the mode ... on the
//    unit circle ..."), or else gives the eigenvalue of the symplectic pencil nearest the unit
//    circle;
//  - R + B'XB is not positive definite at the X found (the message gives its smallest eigenvalue);
//  - the closed loop A − BK that comes out has an eigenvalue on or outside the unit circle.
// The error reporting follows the CARE solvers (riccati.hpp).

#include <Eigen/Dense>

namespace thetad {

struct DareResult {
  Eigen::MatrixXd X;  // stabilizing solution, exactly symmetric
  Eigen::MatrixXd K;  // (R + B'XB)⁻¹(B'XA + S'): the optimal feedback is u = −K x
  Eigen::VectorXcd closed_loop_eigenvalues;  // eig(A − BK), all |λ| < 1
  // ‖A'XA − X − (A'XB + S)K + Q‖_F / max(1, ‖Q‖_F), as CareResult::relative_residual.
  double relative_residual;
  int doublings;    // steps of the doubling algorithm
  int refinements;  // Newton steps after it: 1, or 0 when the step was not taken (see solve_dare)
};

// Beyond this many doublings the error has been squared 64 times: convergence would need the
// closed loop's spectral radius within ~1e-17 of 1, i.e. on the unit circle to working precision.
inline constexpr int kDareDoublings = 64;

// The structure-preserving doubling algorithm (SDA; Chu, Fan and Lin 2005) on the equation with
// the cross term eliminated (A − BR⁻¹S', Q − SR⁻¹S'): quadratic convergence, one n×n LU per step;
// then one Newton step (a Stein equation, through a Lyapunov solve), kept when it does not raise
// the residual above rounding level.
DareResult solve_dare(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                      const Eigen::Ref<const Eigen::MatrixXd>& Q, const Eigen::Ref<const Eigen::MatrixXd>& R,
                      const Eigen::Ref<const Eigen::MatrixXd>& S);

// Without a cross term (S = 0).
DareResult solve_dare(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                      const Eigen::Ref<const Eigen::MatrixXd>& Q, const Eigen::Ref<const Eigen::MatrixXd>& R);

}  // namespace thetad
