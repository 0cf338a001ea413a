#pragma once

// How far (A, B) is from a pair that no feedback stabilizes, in the units of the CARE's input
// weight (docs/model.md §8.4): the smallest
//
//     σ_min [A − λI, B R^{-1/2}]        over the eigenvalues λ of A with Re λ ≥ 0
//
// (the Hautus test: (A, B) is stabilizable exactly when this is positive). It is 0 at a mode that
// the inputs cannot move, and +inf when A has no eigenvalue in the closed right half-plane (nothing
// needs stabilizing). Any W with W Wᵀ = R⁻¹ gives the same singular values as R^{-1/2}: W = L⁻ᵀ
// with R = L Lᵀ here.
//
// An eigenvalue counts when Re λ ≥ −10 √ε ‖A‖_F: a zero eigenvalue in a 2×2 Jordan block (a
// position and its integral, docs/model.md §3.6) is computed up to ~√ε ‖A‖ off the axis. The
// helicopter's bias mode −k_s = −0.1 is far below that and never counts.

#include <Eigen/Dense>

namespace thetad {

// The margin for fixed sizes and R, with every LAPACK workspace sized at construction: evaluate()
// allocates nothing. Not thread-safe per object.
class StabilizabilityMargin {
 public:
  // A n×n, B n×m with m = R.rows(); R symmetric positive definite (checked).
  StabilizabilityMargin(Eigen::Index n, const Eigen::Ref<const Eigen::MatrixXd>& R);

  // The margin of (A, B); throws thetad::Error when a size does not match or LAPACK fails (a
  // non-finite entry).
  double evaluate(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

 private:
  Eigen::Index n_, m_;
  Eigen::MatrixXd weight_;                 // L⁻ᵀ
  Eigen::MatrixXd A_, scaled_input_;       // A as dgeev overwrites it, B L⁻ᵀ
  Eigen::VectorXd real_, imaginary_, eigen_work_;
  Eigen::MatrixXcd pencil_;                // [A − λI, B L⁻ᵀ], overwritten by zgesvd
  Eigen::VectorXd singular_values_, svd_real_work_;
  Eigen::VectorXcd svd_work_;
};

// StabilizabilityMargin(A.rows(), R).evaluate(A, B): a one-off margin.
double stabilizability_margin(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                              const Eigen::Ref<const Eigen::MatrixXd>& R);

}  // namespace thetad
