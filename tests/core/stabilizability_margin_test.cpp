#include "core/stabilizability_margin.hpp"

#include <cmath>
#include <complex>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "core/error.hpp"
#include "tests/core/care_checks.hpp"
#include "tests/linear_algebra.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using testing::scalar;

constexpr double kInf = std::numeric_limits<double>::infinity();


TEST(StabilizabilityMargin, OfAnUnstableScalarIsTheInputOverRootR) {
  // λ = a: σ_min [a − a, b / √r] = |b| / √r, whatever a > 0.
  EXPECT_DOUBLE_EQ(stabilizability_margin(scalar(2.0), scalar(-3.0), scalar(4.0)), 1.5);
  EXPECT_DOUBLE_EQ(stabilizability_margin(scalar(0.5), scalar(1.0), scalar(1e-2)), 10.0);
}

TEST(StabilizabilityMargin, IsInfiniteWithNothingToStabilize) {
  EXPECT_EQ(stabilizability_margin(scalar(-1.0), scalar(0.0), scalar(1.0)), kInf);
  MatrixXd A(2, 2);
  A << -1.0, 5.0, -5.0, -1.0;  // −1 ± 5i
  EXPECT_EQ(stabilizability_margin(A, MatrixXd::Zero(2, 1), scalar(1.0)), kInf);
}

TEST(StabilizabilityMargin, IsZeroAtAnUncontrollableUnstableMode) {
  // diag(1, −2) with the input on the stable mode only, in a rotated basis so that nothing is exact.
  const double angle = 0.7;
  MatrixXd T(2, 2);
  T << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  const MatrixXd A = T * Eigen::Vector2d(1.0, -2.0).asDiagonal() * T.transpose();
  const MatrixXd B = T * Eigen::Vector2d(0.0, 1.0);
  EXPECT_NEAR(stabilizability_margin(A, B, scalar(1.0)), 0.0, 1e-15);
  // A zero eigenvalue counts (Re λ ≥ 0): a pure integrator without an input.
  EXPECT_EQ(stabilizability_margin(scalar(0.0), scalar(0.0), scalar(1.0)), 0.0);
}

TEST(StabilizabilityMargin, LeavesAStableUncontrollableModeOut) {
  // The bias mode −k_s = −0.1 with no input: counted, λ = −0.1 would give 0. Only λ = 1 counts:
  // [A − I, B] = [[−1.1, 0, 0], [0, 0, 1]] has singular values 1.1 and 1.
  const MatrixXd A = Eigen::Vector2d(-0.1, 1.0).asDiagonal();
  const MatrixXd B = Eigen::Vector2d(0.0, 1.0);
  EXPECT_NEAR(stabilizability_margin(A, B, scalar(1.0)), 1.0, 1e-15);
}

TEST(StabilizabilityMargin, CountsAZeroEigenvalueOfAJordanBlock) {
  // A position and its integral: a 2×2 Jordan block at 0; the input drives the position. At λ = 0,
  // [A, B] = [[0, 0, 1], [1, 0, 0]]: singular values 1, 1.
  MatrixXd A = MatrixXd::Zero(2, 2);
  A(1, 0) = 1.0;
  const MatrixXd B = Eigen::Vector2d(1.0, 0.0);
  EXPECT_NEAR(stabilizability_margin(A, B, scalar(1.0)), 1.0, 1e-15);
  // Without the input the integral chain is not stabilizable.
  EXPECT_NEAR(stabilizability_margin(A, MatrixXd::Zero(2, 1), scalar(1.0)), 0.0, 1e-15);
}

// The definition evaluated by Eigen's own eigen- and singular-value solvers, with the symmetric
// R^{-1/2} rather than the Cholesky factor the class uses.
double margin_by_definition(const MatrixXd& A, const MatrixXd& B, const MatrixXd& R) {
  const Eigen::SelfAdjointEigenSolver<MatrixXd> r(R);
  const MatrixXd root_inverse = r.operatorInverseSqrt();
  const Eigen::VectorXcd eigenvalues = testing::eigenvalues_of(A);
  const auto n = A.rows(), m = B.cols();
  double margin = kInf;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (eigenvalues[k].real() < 0.0) continue;
    Eigen::MatrixXcd pencil(n, n + m);
    pencil.leftCols(n) = A.cast<std::complex<double>>() - eigenvalues[k] * Eigen::MatrixXcd::Identity(n, n);
    pencil.rightCols(m) = (B * root_inverse).cast<std::complex<double>>();
    margin = std::min(margin, testing::singular_values_of(pencil)(n - 1));
  }
  return margin;
}

TEST(StabilizabilityMargin, MatchesTheDefinitionOnRandomPairs) {
  std::mt19937_64 rng(34);
  std::normal_distribution<double> normal;
  const auto draw = [&](Eigen::Index rows, Eigen::Index cols) {
    return MatrixXd(MatrixXd::NullaryExpr(rows, cols, [&] { return normal(rng); }));
  };
  StabilizabilityMargin margin(6, MatrixXd::Identity(2, 2));
  for (int trial = 0; trial < 20; ++trial) {
    const MatrixXd A = draw(6, 6), B = draw(6, 2), L = draw(2, 2);
    const MatrixXd R = L * L.transpose() + 0.5 * MatrixXd::Identity(2, 2);
    const double expected = margin_by_definition(A, B, R);
    EXPECT_NEAR(stabilizability_margin(A, B, R), expected, 1e-12 * std::max(1.0, expected)) << "trial " << trial;
    if (trial == 0) {
      EXPECT_NEAR(margin.evaluate(A, B), margin_by_definition(A, B, MatrixXd::Identity(2, 2)), 1e-12);
    }
  }
}

TEST(StabilizabilityMargin, RefusesWrongSizesAndAnIndefiniteR) {
  EXPECT_THROW(StabilizabilityMargin(2, scalar(-1.0)), Error);
  StabilizabilityMargin margin(2, scalar(1.0));
  EXPECT_THROW(margin.evaluate(MatrixXd::Zero(3, 3), MatrixXd::Zero(3, 1)), Error);
}

}  // namespace
}  // namespace thetad
