#include "core/matrix_sign.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <random>

#include <gtest/gtest.h>

#include "tests/linear_algebra.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Z = V diag(λ) V⁻¹ with real λ: sign(Z) = V diag(sign λ) V⁻¹.
struct KnownSign {
  MatrixXd Z;
  MatrixXd sign;
  // First-order bound on the error of any backward-stable computation of sign(Z): a change δZ
  // moves sign(Z) by at most κ(V)² · max 2/|λi − λj| (pairs of opposite sign) · ‖δZ‖, and
  // rounding makes ‖δZ‖ ≈ u‖Z‖. Ten times that, for the rounding of the iteration itself.
  double bound;
};

KnownSign known_sign(const VectorXd& eigenvalues, const MatrixXd& V) {
  const Eigen::Index n = eigenvalues.size();
  const Eigen::PartialPivLU<MatrixXd> lu(V);
  const VectorXd singular = testing::singular_values_of(V);
  const double kappa = singular(0) / singular(n - 1);
  double divided_difference = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      if (eigenvalues(i) * eigenvalues(j) < 0)
        divided_difference = std::max(divided_difference, 2.0 / std::abs(eigenvalues(i) - eigenvalues(j)));
  const MatrixXd Z = V * eigenvalues.asDiagonal() * lu.inverse();
  const double u = std::numeric_limits<double>::epsilon() / 2;
  return {Z, V * VectorXd(eigenvalues.array().sign()).asDiagonal() * lu.inverse(),
          10.0 * kappa * kappa * divided_difference * u * Z.norm()};
}

MatrixXd random_matrix(Eigen::Index n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  return MatrixXd::NullaryExpr(n, n, [&] { return normal(rng); });
}

// Alternating signs, magnitudes spread evenly in log scale over [10^low, 10^high].
VectorXd spread(int n, double low, double high) {
  VectorXd eigenvalues(n);
  for (int i = 0; i < n; ++i)
    eigenvalues(i) = (i % 2 == 0 ? 1.0 : -1.0) * std::pow(10.0, low + (high - low) * i / std::max(1, n - 1));
  return eigenvalues;
}

void expect_sign(const KnownSign& case_, const std::string& what) {
  const Eigen::Index n = case_.Z.rows();
  const auto result = matrix_sign(case_.Z, 40);
  ASSERT_TRUE(result) << what;
  EXPECT_LE((result->sign - case_.sign).norm(), case_.bound) << what;
  EXPECT_LE((result->sign * result->sign - MatrixXd::Identity(n, n)).norm(), 2.0 * case_.bound) << what << ": sign² = I";
  EXPECT_GE(result->iterations, 1) << what;
  EXPECT_LE(result->iterations, 15) << what << ": determinant scaling needs few inversions";
}

TEST(MatrixSign, NormalMatricesOverSixDecades) {
  std::mt19937_64 rng(7);
  for (int n : {1, 2, 5, 12, 36}) {
    const MatrixXd V = random_matrix(n, rng).householderQr().householderQ();
    expect_sign(known_sign(spread(n, -3, 3), V), "orthogonal V, n = " + std::to_string(n));
  }
}

TEST(MatrixSign, NonNormalMatrices) {
  std::mt19937_64 rng(8);
  for (int n : {2, 5, 12, 36}) {
    const MatrixXd V = random_matrix(n, rng) + 2.0 * MatrixXd::Identity(n, n);
    expect_sign(known_sign(spread(n, -1, 1), V), "general V, n = " + std::to_string(n));
  }
}

TEST(MatrixSign, ComplexEigenvaluesKeepTheSignOfTheirRealPart) {
  // Rotation-dilation blocks: eigenvalues 0.5 ± 3i and −2 ± 0.1i.
  MatrixXd Z = MatrixXd::Zero(4, 4);
  Z.topLeftCorner(2, 2) << 0.5, 3, -3, 0.5;
  Z.bottomRightCorner(2, 2) << -2, 0.1, -0.1, -2;
  const auto result = matrix_sign(Z, 40);
  ASSERT_TRUE(result);
  MatrixXd expected = MatrixXd::Identity(4, 4);
  expected.bottomRightCorner(2, 2) *= -1.0;
  EXPECT_LE((result->sign - expected).norm(), 1e-14);
}

TEST(MatrixSign, EigenvaluesOnTheImaginaryAxisGiveNothing) {
  MatrixXd rotation(2, 2);  // ±i: the first Newton step lands on the zero matrix
  rotation << 0, 1, -1, 0;
  EXPECT_FALSE(matrix_sign(rotation, 40));
  MatrixXd singular(2, 2);  // an eigenvalue at 0
  singular << 1, 2, 2, 4;
  EXPECT_FALSE(matrix_sign(singular, 40));
}

TEST(MatrixSign, ANormalMatrixCloseToTheAxisStillGetsItsSign) {
  // λ = ±1e-9 + ±i: one Newton step maps them to ≈ ±2e-9, the scaled steps after that to ±1.
  for (const double re : {1e-9, -1e-9}) {
    MatrixXd Z(2, 2);
    Z << re, 1, -1, re;
    const auto result = matrix_sign(Z, 40);
    ASSERT_TRUE(result);
    EXPECT_LE((result->sign - std::copysign(1.0, re) * MatrixXd::Identity(2, 2)).norm(), 1e-12) << "Re λ = " << re;
  }
}

TEST(MatrixSign, GivesNothingWhenNotConvergedWithinTheLimit) {
  std::mt19937_64 rng(11);
  VectorXd eigenvalues(6);
  eigenvalues << 1e-4, -1e-3, 1, -10, 1e3, -1e4;
  const KnownSign case_ = known_sign(eigenvalues, random_matrix(6, rng) + 2.0 * MatrixXd::Identity(6, 6));
  EXPECT_FALSE(matrix_sign(case_.Z, 2));
  const auto result = matrix_sign(case_.Z, 40);
  ASSERT_TRUE(result);
  EXPECT_GT(result->iterations, 2);
}

}  // namespace
}  // namespace thetad
