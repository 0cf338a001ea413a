#pragma once

// The matrix sign function: for Z with no eigenvalue on the imaginary axis, sign(Z) has the
// eigenvectors of Z and the eigenvalues ±1 (the sign of Re λ). The stable invariant subspace of Z
// is the null space of sign(Z) + I, which is how solve_care uses it (riccati.cpp).
//
// Newton's iteration Z ← (cZ + (cZ)⁻¹)/2 with determinant scaling c = |det Z|^(−1/N) until the
// iterates settle (Byers 1987; Higham, Functions of Matrices, §5.5).

#include <optional>

#include <Eigen/Dense>

namespace thetad {

struct MatrixSign {
  Eigen::MatrixXd sign;
  int iterations;  // matrix inversions
};

// The iteration for one size N, with every buffer sized at construction: compute() allocates
// nothing (CareSolver's cold solve in a control step). Not thread-safe per object.
class MatrixSignSolver {
 public:
  explicit MatrixSignSolver(Eigen::Index N);

  // sign(Z) into sign(), and the inversions it took. Empty when an iterate is singular to working
  // precision (Z has an eigenvalue at, or the iteration met one on, the imaginary axis) or the
  // iteration has not converged after max_iterations inversions, which happens when eigenvalues
  // lie close to the axis: the caller then needs an eigenvalue method to say why.
  std::optional<int> compute(const Eigen::Ref<const Eigen::MatrixXd>& Z, int max_iterations);
  const Eigen::MatrixXd& sign() const { return Z_; }

 private:
  // inverse_ = U⁻¹L⁻¹ from PZ = LU: Z⁻¹ with its columns permuted.
  void invert_factored();

  Eigen::MatrixXd Z_, next_, inverse_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
};

// One sign function, for a one-off matrix: MatrixSignSolver(Z.rows()).compute(Z, max_iterations).
std::optional<MatrixSign> matrix_sign(const Eigen::Ref<const Eigen::MatrixXd>& Z, int max_iterations);

}  // namespace thetad
