#include "core/lyapunov.hpp"

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <new>
#include <random>

#include <Eigen/Eigenvalues>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tests/heap_counter.hpp"
#include "tests/linear_algebra.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using ::testing::HasSubstr;

MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  MatrixXd M(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) M(i, j) = normal(rng);
  return M;
}

// A non-normal stable matrix whose eigenvalues keep a margin of 0.5 from the imaginary axis.
MatrixXd random_stable(Eigen::Index n, std::mt19937_64& rng) {
  MatrixXd A = random_matrix(n, n, rng) / std::sqrt(static_cast<double>(n));
  const double max_real = testing::max_real_eigenvalue(A);
  A -= (max_real + 0.5) * MatrixXd::Identity(n, n);
  return A;
}

MatrixXd random_symmetric_psd(Eigen::Index n, std::mt19937_64& rng) {
  const MatrixXd C = random_matrix(n, n, rng);
  // A product is symmetric only up to rounding; symmetric means exactly symmetric here.
  const MatrixXd Q = C * C.transpose();
  return 0.5 * (Q + Q.transpose());
}

double relative_residual(const MatrixXd& A, const MatrixXd& X, const MatrixXd& Q) {
  return (A.transpose() * X + X * A + Q).norm() / Q.norm();
}

TEST(SolveLyapunov, ScalarClosedForm) {
  // 2 a x + q = 0.
  const MatrixXd X = solve_lyapunov(MatrixXd::Constant(1, 1, -2.0), MatrixXd::Constant(1, 1, 3.0));
  EXPECT_DOUBLE_EQ(X(0, 0), 0.75);
}

TEST(SolveLyapunov, DiagonalClosedForm) {
  // x_ij = −q_ij / (a_i + a_j) for A = diag(a).
  const Eigen::Vector4d a(-0.1, -1.0, -7.0, -250.0);
  std::mt19937_64 rng(7);
  const MatrixXd Q = random_symmetric_psd(4, rng);
  const MatrixXd X = solve_lyapunov(a.asDiagonal().toDenseMatrix(), Q);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR(X(i, j), -Q(i, j) / (a(i) + a(j)), 1e-14 * std::abs(Q(i, j) / (a(i) + a(j))));
}

TEST(SolveLyapunov, SmallResidualOnRandomStableMatrices) {
  std::mt19937_64 rng(20240601);
  for (Eigen::Index n = 1; n <= 40; ++n) {
    const MatrixXd A = random_stable(n, rng);
    const MatrixXd Q = random_symmetric_psd(n, rng);
    const MatrixXd X = solve_lyapunov(A, Q);
    EXPECT_LE(relative_residual(A, X, Q), 1e-12) << "n = " << n;
    EXPECT_EQ(X, X.transpose()) << "n = " << n;
  }
}

TEST(SolveLyapunov, AcceptsNonSymmetricQ) {
  std::mt19937_64 rng(3);
  const MatrixXd A = random_stable(6, rng);
  const MatrixXd Q = random_matrix(6, 6, rng);
  EXPECT_LE(relative_residual(A, solve_lyapunov(A, Q), Q), 1e-12);
}

TEST(SolveLyapunov, ThrowsWhenEigenvaluesSumToZero) {
  // Eigenvalues ±1 hidden behind a similarity: λ1 + λ2 = 0.
  Eigen::Matrix2d S;
  S << 1.0, 2.0, 0.5, 3.0;
  const MatrixXd A = S * Eigen::Vector2d(1.0, -1.0).asDiagonal() * S.inverse();
  EXPECT_THAT([&] { solve_lyapunov(A, MatrixXd::Identity(2, 2)); },
              ::testing::ThrowsMessage<Error>(HasSubstr("min |λi(A) + λj(A)| = ")));
}

TEST(SolveLyapunov, ThrowsOnImaginaryAxisEigenvalue) {
  Eigen::Matrix2d A;
  A << 0.0, 1.0, -1.0, 0.0;  // ±j
  EXPECT_THAT([&] { solve_lyapunov(A, MatrixXd::Identity(2, 2)); },
              ::testing::ThrowsMessage<Error>(HasSubstr("singular to working precision")));
}

TEST(SolveLyapunov, ThrowsOnBadInput) {
  EXPECT_THAT([] { solve_lyapunov(-MatrixXd::Identity(2, 2), MatrixXd::Identity(3, 3)); },
              ::testing::ThrowsMessage<Error>(HasSubstr("Q must have the size of A (2x2), got 3x3")));
  EXPECT_THAT([] { solve_lyapunov(MatrixXd::Zero(2, 3), MatrixXd::Identity(2, 3)); },
              ::testing::ThrowsMessage<Error>(HasSubstr("A must be square, got 2x3")));
  MatrixXd Q = MatrixXd::Identity(2, 2);
  Q(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT([&] { solve_lyapunov(-MatrixXd::Identity(2, 2), Q); },
              ::testing::ThrowsMessage<Error>(HasSubstr("Q has non-finite entries")));
}

TEST(ConstantLyapunovSolver, AgreesWithSolveLyapunov) {
  std::mt19937_64 rng(11);
  for (Eigen::Index n : {1, 2, 3, 5, 8, 13, 18, 27}) {
    const MatrixXd A = random_stable(n, rng);
    const ConstantLyapunovSolver solver(A);
    EXPECT_LT(solver.max_real_eigenvalue(), 0.0);
    for (int trial = 0; trial < 3; ++trial) {
      const MatrixXd Q = random_symmetric_psd(n, rng);
      const MatrixXd X = solver.solve(Q);
      const MatrixXd reference = solve_lyapunov(A, Q);
      EXPECT_LE((X - reference).norm(), 1e-12 * reference.norm()) << "n = " << n;
      EXPECT_LE(relative_residual(A, X, Q), 1e-12) << "n = " << n;
      EXPECT_EQ(X, X.transpose());
    }
  }
}

TEST(ConstantLyapunovSolver, WideEigenvalueSpreadLikeThePaper) {
  // The θ–D Ac0 (docs/model.md §13) has eigenvalues from −0.1 to −219: the same spread here,
  // behind a non-orthogonal similarity, with weights spanning nine decades as in §7.2. (With a
  // stronger similarity, 0.3 instead of 0.1, the operator's condition number reaches 2e7 and
  // both methods' residuals rise together to ~5e-11: the limit is the problem, not the method.)
  std::mt19937_64 rng(18);
  const Eigen::Index n = 18;
  Eigen::VectorXd eigenvalues = -Eigen::VectorXd::LinSpaced(n, std::log(0.1), std::log(219.0)).array().exp();
  const MatrixXd S = MatrixXd::Identity(n, n) + 0.1 * random_matrix(n, n, rng);
  const MatrixXd A = S * eigenvalues.asDiagonal() * S.inverse();
  const ConstantLyapunovSolver solver(A);
  EXPECT_LT(solver.condition_number(), 1e5);
  Eigen::VectorXd weights = Eigen::VectorXd::LinSpaced(n, 0.0, 9.0);
  weights = weights.unaryExpr([](double e) { return std::pow(10.0, e); });
  const MatrixXd Q = weights.asDiagonal();
  const MatrixXd X = solver.solve(Q);
  EXPECT_LE(relative_residual(A, X, Q), 1e-13);
  const MatrixXd reference = solve_lyapunov(A, Q);
  EXPECT_LE((X - reference).norm(), 1e-12 * reference.norm());
}

TEST(ConstantLyapunovSolver, ThrowsWhenNotHurwitz) {
  Eigen::Matrix2d A;
  A << -1.0, 3.0, 0.0, 0.5;
  EXPECT_THAT([&] { ConstantLyapunovSolver solver(A); },
              ::testing::ThrowsMessage<Error>(
                  AllOf(HasSubstr("not Hurwitz"), HasSubstr("max Re λ(Ac) = 0.5"))));
  EXPECT_THAT([] { ConstantLyapunovSolver solver(MatrixXd::Zero(3, 3)); },
              ::testing::ThrowsMessage<Error>(HasSubstr("max Re λ(Ac) = 0")));
}

TEST(ConstantLyapunovSolver, ThrowsOnBadInput) {
  EXPECT_THAT([] { ConstantLyapunovSolver solver(MatrixXd::Zero(2, 3)); },
              ::testing::ThrowsMessage<Error>(HasSubstr("Ac must be square, got 2x3")));
  const ConstantLyapunovSolver solver(-MatrixXd::Identity(3, 3));
  MatrixXd X(3, 3);
  EXPECT_THAT([&] { solver.solve(MatrixXd::Identity(2, 2), X); },
              ::testing::ThrowsMessage<Error>(HasSubstr("Q and X must be 3x3, got Q 2x2")));
}

TEST(ConstantLyapunovSolver, SolveAllocatesNothing) {
  std::mt19937_64 rng(5);
  const Eigen::Index n = 18;
  const ConstantLyapunovSolver solver(random_stable(n, rng));
  const MatrixXd Q = random_symmetric_psd(n, rng);
  MatrixXd X(n, n);
  // The counter must see a real allocation, or a zero below would prove nothing.
  MatrixXd probe;
  const long probe_allocations = thetad::testing::heap_allocations_during([&] { probe = solver.solve(Q); });
  if (probe_allocations < 0) GTEST_SKIP() << "malloc cannot be interposed in this build (AddressSanitizer)";
  EXPECT_GT(probe_allocations, 0);

  EXPECT_EQ(thetad::testing::heap_allocations_during([&] {
              for (int i = 0; i < 10; ++i) solver.solve(Q, X);
            }),
            0);
  EXPECT_EQ(X, probe);
}

}  // namespace
}  // namespace thetad
