// The exported step's Lyapunov solver (export/onboard/lyapunov_schur.hpp, a plain-loop port of the
// library's Bartels–Stewart) against the library's LyapunovWorkspace: the Schur form is a Schur
// form of A, the eigenvalues and X agree to rounding on random stable matrices with 2×2 blocks,
// and it refuses what the library refuses, by status.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "core/lyapunov.hpp"
#include "export/onboard/helicopter_sdc.hpp"
#include "export/onboard/lyapunov_schur.hpp"

namespace thetad {
namespace {

constexpr int kN = 18;
using thetad_onboard::Status;
using RowMatrix = Eigen::Matrix<double, kN, kN, Eigen::RowMajor>;

// A random Hurwitz matrix (shifted normal: complex pairs and real eigenvalues) and a symmetric Q.
RowMatrix stable_matrix(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  RowMatrix A;
  for (int e = 0; e < kN * kN; ++e) A.data()[e] = normal(rng);
  const double shift = Eigen::MatrixXd(A).eigenvalues().real().maxCoeff() + 0.5;
  return A - shift * RowMatrix::Identity();
}

TEST(OnboardLyapunov, SchurFormAndSolutionMatchTheLibrary) {
  std::mt19937_64 rng(3);
  static thetad_onboard::SchurWorkspace<double, kN> w;
  for (int trial = 0; trial < 20; ++trial) {
    const RowMatrix A = stable_matrix(rng);
    RowMatrix Q = RowMatrix::Random();
    Q = (Q + Q.transpose()).eval();
    ASSERT_EQ(thetad_onboard::real_schur(A.data(), w), Status::ok) << trial;
    const Eigen::Map<const RowMatrix> T(w.t), U(w.u);
    EXPECT_LE((U * T * U.transpose() - A).norm(), 1e-13 * A.norm()) << trial;
    EXPECT_LE((U.transpose() * U - RowMatrix::Identity()).norm(), 1e-13) << trial;
    for (int r = 0; r < kN; ++r)
      for (int c = 0; c + 1 < r; ++c) EXPECT_EQ(T(r, c), 0.0);
    LyapunovWorkspace library(kN);
    library.factor(A);
    EXPECT_LE((Eigen::Map<const Eigen::VectorXd>(w.wr, kN) - library.eigenvalues_real()).norm(), 1e-12 * A.norm());
    RowMatrix X;
    ASSERT_EQ(thetad_onboard::lyapunov_solve(w, Q.data(), X.data()), Status::ok);
    Eigen::MatrixXd expected(kN, kN);
    library.solve(Q, expected);
    EXPECT_EQ(X, X.transpose());
    EXPECT_LE((Eigen::MatrixXd(X) - expected).norm(), 1e-12 * expected.norm()) << trial;
    EXPECT_LE((A.transpose() * X + X * A + Q).norm(), 1e-12 * (2.0 * A.norm() * X.norm() + Q.norm())) << trial;
  }
}

TEST(OnboardLyapunov, FloatSolvesToItsRounding) {
  std::mt19937_64 rng(5);
  static thetad_onboard::SchurWorkspace<float, kN> w;
  const RowMatrix A = stable_matrix(rng);
  const RowMatrix Q = RowMatrix::Identity();
  const Eigen::Matrix<float, kN, kN, Eigen::RowMajor> Af = A.cast<float>(), Qf = Q.cast<float>();
  Eigen::Matrix<float, kN, kN, Eigen::RowMajor> X;
  ASSERT_EQ(thetad_onboard::real_schur(Af.data(), w), Status::ok);
  ASSERT_EQ(thetad_onboard::lyapunov_solve(w, Qf.data(), X.data()), Status::ok);
  const Eigen::MatrixXd expected = solve_lyapunov(A, Q);
  EXPECT_LE((X.cast<double>() - expected).norm(), 1e-4 * expected.norm());
}

TEST(OnboardLyapunov, RefusesASingularOperatorAndNonFiniteEntriesByStatus) {
  static thetad_onboard::SchurWorkspace<double, kN> w;
  RowMatrix A = RowMatrix::Zero();  // every λi + λj = 0
  ASSERT_EQ(thetad_onboard::real_schur(A.data(), w), Status::ok);
  RowMatrix X;
  const RowMatrix Q = RowMatrix::Identity();
  EXPECT_EQ(thetad_onboard::lyapunov_solve(w, Q.data(), X.data()), Status::lyapunov_singular);
  A(3, 4) = std::nan("");
  EXPECT_EQ(thetad_onboard::real_schur(A.data(), w), Status::not_finite);
}

}  // namespace
}  // namespace thetad
