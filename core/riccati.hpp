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

#include <memory>

#include <Eigen/Dense>

#include "core/care_result.hpp"
#include "core/newton_kleinman.hpp"

namespace thetad {

// How solve_care finds the stable invariant subspace of the Hamiltonian
// H = [A, −G; −Q, −A'], G = B R⁻¹ B'. docs/riccati.md compares them with SLICOT SB02MD.
enum class CareMethod {
  // The matrix sign function, and Laub's Schur method whenever the sign iteration fails (a
  // Hamiltonian eigenvalue on or near the imaginary axis, no stabilizing solution) or its
  // solution is not backward stable: the speed of the first, the diagnostics of the second. Then,
  // on equations whose terms dwarf Q (weights spanning decades), one Newton step with the
  // residual in compensated arithmetic (care_refinement.hpp), which brings the forward error to
  // that of SLICOT SB02OD or below (docs/riccati.md).
  automatic,
  // Newton's iteration for sign(H); P from the null space of sign(H) + I (Roberts 1971, Byers
  // 1987). 8–13 inversions of the 2n×2n H instead of an ordered Schur form: faster at the
  // paper's size. Throws when the iteration fails, without saying which precondition is broken,
  // or when its solution is not backward stable even after Newton refinement.
  matrix_sign,
  // Laub's method: the ordered real Schur form of the balanced H gives a basis [U1; U2] of its
  // stable invariant subspace and P = U2 U1⁻¹ (the method of SLICOT SB02MD and MATLAB care).
  schur,
};

// The direct solver for fixed weights Q, R and fixed sizes: the SDRE's cold step. Every buffer and
// LAPACK workspace is sized at construction; solve() allocates nothing unless it throws (a failure
// names the precondition the data break, care_diagnosis.hpp). Not thread-safe per object.
class CareSolver {
 public:
  // Q n×n symmetric positive semi-definite, R m×m symmetric positive definite (checked). The
  // proof only matters on the matrix-sign path: the Schur method has the closed-loop spectrum for
  // free, unless a Newton refinement moved P.
  // estimates: whether solve() fills CareResult::forward_error and condition (its cost there).
  CareSolver(const Eigen::Ref<const Eigen::MatrixXd>& Q, const Eigen::Ref<const Eigen::MatrixXd>& R,
             CareMethod method = CareMethod::automatic, StabilityProof proof = StabilityProof::spectrum,
             ErrorEstimates estimates = ErrorEstimates::off);
  ~CareSolver();
  CareSolver(const CareSolver& other);
  CareSolver& operator=(const CareSolver&) = delete;

  // The stabilizing solution for (A, B), with the errors listed at the top of this file. The
  // result lives in this object until the next call.
  const CareResult& solve(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

 private:
  struct Workspace;
  std::unique_ptr<Workspace> workspace_;
};

// The direct solver for a one-off equation: CareSolver(Q, R, method, spectrum, estimates).solve(A,
// B); no initial guess needed.
CareResult solve_care(const Eigen::Ref<const Eigen::MatrixXd>& A,
                      const Eigen::Ref<const Eigen::MatrixXd>& B,
                      const Eigen::Ref<const Eigen::MatrixXd>& Q,
                      const Eigen::Ref<const Eigen::MatrixXd>& R,
                      CareMethod method = CareMethod::automatic,
                      ErrorEstimates estimates = ErrorEstimates::off);

// With a cross term N (the LQR cost x'Qx + u'Ru + 2x'Nu): the CARE of A − BR⁻¹N' and Q − NR⁻¹N'
// (care::eliminate_cross_term), which must be positive semi-definite, and K = R⁻¹(B'P + N').
CareResult solve_care(const Eigen::Ref<const Eigen::MatrixXd>& A,
                      const Eigen::Ref<const Eigen::MatrixXd>& B,
                      const Eigen::Ref<const Eigen::MatrixXd>& Q,
                      const Eigen::Ref<const Eigen::MatrixXd>& R,
                      const Eigen::Ref<const Eigen::MatrixXd>& N,
                      CareMethod method = CareMethod::automatic,
                      ErrorEstimates estimates = ErrorEstimates::off);

}  // namespace thetad
