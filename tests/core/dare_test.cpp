// solve_dare (core/dare.hpp): random stabilizable problems from n = 2 to 40, closed forms, DAREX
// examples (Benner, Laub and Mehrmann 1995), a closed loop near the unit circle, weights of any
// size, the cross term, and every refusal with its reason.
#include "core/dare.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Dense>

#include "core/machine_epsilon.hpp"
#include "tests/core/care_checks.hpp"
#include "tests/error_message.hpp"
#include "tests/linear_algebra.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using ::testing::HasSubstr;
using testing::error_message;
using testing::scalar;

// Expects `result` to be the stabilizing solution: X exactly symmetric, the normwise residual
// ‖A'XA − X − (A'XB + S)K + Q‖_F / (‖Q‖_F + ‖A‖_F²‖X‖_F + ‖X‖_F) within `tol`·n·ε, K = (R +
// B'XB)⁻¹(B'XA + S'), the reported residual the recomputed one, every closed-loop eigenvalue
// (reported and recomputed) inside the unit circle.
void expect_valid_dare(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, const MatrixXd& S,
                       const DareResult& result, double tol = 10.0) {
  const Eigen::Index n = A.rows();
  ASSERT_EQ(result.X.rows(), n);
  ASSERT_EQ(result.K.rows(), B.cols());
  ASSERT_TRUE(result.X.allFinite());
  EXPECT_EQ((result.X - result.X.transpose()).norm(), 0.0) << "X is not symmetric";
  const MatrixXd& X = result.X;
  const MatrixXd coupling = B.transpose() * X * A + S.transpose();
  const MatrixXd curvature = R + B.transpose() * X * B;
  EXPECT_LE((curvature * result.K - coupling).norm(), 1e-12 * curvature.norm() * result.K.norm() + 1e-300);
  const MatrixXd residual = A.transpose() * X * A - X - coupling.transpose() * result.K + Q;
  const double terms = Q.norm() + A.norm() * A.norm() * X.norm() + X.norm();
  EXPECT_LE(residual.norm(), tol * static_cast<double>(n) * kEps * terms) << "size of the terms " << terms;
  EXPECT_NEAR(result.relative_residual, residual.norm() / std::max(1.0, Q.norm()), 1e-13 * terms / std::max(1.0, Q.norm()));
  EXPECT_LT(result.closed_loop_eigenvalues.cwiseAbs().maxCoeff(), 1.0);
  const Eigen::VectorXcd recomputed = testing::eigenvalues_of(A - B * result.K);
  EXPECT_LT(recomputed.cwiseAbs().maxCoeff(), 1.0);
  EXPECT_GT(result.doublings, 0);
  EXPECT_LE(result.doublings, kDareDoublings);
  EXPECT_GE(result.refinements, 0);
  EXPECT_LE(result.refinements, 1);
}

MatrixXd no_cross_term(const MatrixXd& B) { return MatrixXd::Zero(B.rows(), B.cols()); }

TEST(Dare, RandomStabilizableProblemsToRoundingLevel) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const auto random = [&](Eigen::Index rows, Eigen::Index cols) {
    return MatrixXd(MatrixXd::NullaryExpr(rows, cols, [&] { return normal(rng); }));
  };
  for (int n = 2; n <= 40; n += 2) {
    for (int draw = 0; draw < 3; ++draw) {
      const Eigen::Index m = 1 + n / 4;
      // Open-loop spectral radius about 1.3: unstable modes, which a full-rank B reaches.
      const MatrixXd A = 1.3 * random(n, n) / std::sqrt(static_cast<double>(n));
      const MatrixXd B = random(n, m);
      const MatrixXd C = random(n, n);
      const MatrixXd Q = C.transpose() * C;
      const MatrixXd G = random(m, m);
      const MatrixXd R = G * G.transpose() + MatrixXd::Identity(m, m);
      SCOPED_TRACE("n = " + std::to_string(n) + ", draw " + std::to_string(draw));
      expect_valid_dare(A, B, Q, R, no_cross_term(B), solve_dare(A, B, Q, R));
    }
  }
}

// x = a²x − a²b²x²/(r + b²x) + q, i.e. b²x² + (r(1 − a²) − qb²)x − qr = 0: its positive root.
TEST(Dare, ScalarEquationHasItsClosedForm) {
  for (const double a : {-3.0, 0.0, 0.5, 1.0, 2.0}) {
    for (const double b : {0.1, 1.0, 5.0}) {
      const double q = 2.0, r = 0.7;
      const double p = r * (1.0 - a * a) - q * b * b;
      const double x = (-p + std::sqrt(p * p + 4.0 * b * b * q * r)) / (2.0 * b * b);
      const DareResult result = solve_dare(scalar(a), scalar(b), scalar(q), scalar(r));
      // The Newton step on a residual at rounding level moves x by a few ε (14ε measured at a = −3).
      EXPECT_NEAR(result.X(0, 0), x, 32.0 * kEps * x) << "a = " << a << ", b = " << b;
      expect_valid_dare(scalar(a), scalar(b), scalar(q), scalar(r), scalar(0.0), result);
    }
  }
}

// DAREX 1.3: X = [1, 2; 2, 2 + √5].
TEST(Dare, DarexExample13) {
  const MatrixXd A = (MatrixXd(2, 2) << 0, 1, 0, 0).finished();
  const MatrixXd B = (MatrixXd(2, 1) << 0, 1).finished();
  const MatrixXd Q = (MatrixXd(2, 2) << 1, 2, 2, 4).finished();
  const DareResult result = solve_dare(A, B, Q, scalar(1.0));
  const MatrixXd X = (MatrixXd(2, 2) << 1, 2, 2, 2 + std::sqrt(5.0)).finished();
  EXPECT_LE((result.X - X).norm(), 8.0 * kEps * X.norm());
  expect_valid_dare(A, B, Q, scalar(1.0), no_cross_term(B), result);
}

// A marginally stable plant, barely weighted: the closed loop's spectral radius is ρ = 1 − O(√q),
// and the doubling's error shrinks as ρ^(2^k). q = 1e-20 leaves 1 − 1e-10: ~40 doublings, after
// which the doubling's x was off by 3.6e-9 relative; the Newton step brings it to rounding level.
TEST(Dare, ClosedLoopNearTheUnitCircle) {
  for (const double q : {1e-4, 1e-12, 1e-20}) {
    const DareResult result = solve_dare(scalar(1.0), scalar(1.0), scalar(q), scalar(1.0));
    const double x = (q + std::sqrt(q * q + 4.0 * q)) / 2.0;  // the closed form above with a = b = r = 1
    EXPECT_LT(std::abs(result.closed_loop_eigenvalues(0)), 1.0);
    EXPECT_NEAR(result.X(0, 0), x, 8.0 * kEps * x) << "q = " << q;
    EXPECT_LT(result.doublings, 48);
    EXPECT_EQ(result.refinements, 1);
  }
}

// Q, R (hence X) scaled together: the doubling's I + GH does not change, nor does its accuracy.
TEST(Dare, WeightsOfAnySize) {
  const MatrixXd A = (MatrixXd(3, 3) << 1.1, 0.2, 0, 0, 0.9, 0.3, 0.1, 0, 1.05).finished();
  const MatrixXd B = (MatrixXd(3, 2) << 1, 0, 0, 0.5, 0.2, 1).finished();
  const MatrixXd Q = Eigen::Vector3d(1, 1e3, 1e-2).asDiagonal();
  const MatrixXd R = Eigen::Vector2d(1e-1, 10).asDiagonal();
  const MatrixXd X1 = solve_dare(A, B, Q, R).X;
  for (const double s : {1e-150, 1e-20, 1e20, 1e150}) {
    const DareResult result = solve_dare(A, B, s * Q, s * R);
    EXPECT_LE((result.X / s - X1).norm(), 1e-13 * X1.norm()) << "scaled by " << s;
  }
}

// With a cross term: the residual of the equation as given, and the same gain as the cost written
// out without it (u = v − R⁻¹S'x).
TEST(Dare, CrossTerm) {
  const MatrixXd A = (MatrixXd(2, 2) << 1.2, 1, 0, 0.8).finished();
  const MatrixXd B = (MatrixXd(2, 1) << 0, 1).finished();
  const MatrixXd Q = (MatrixXd(2, 2) << 2, 0.5, 0.5, 1).finished();
  const MatrixXd S = (MatrixXd(2, 1) << 0.3, -0.2).finished();
  const MatrixXd R = scalar(0.5);
  const DareResult result = solve_dare(A, B, Q, R, S);
  expect_valid_dare(A, B, Q, R, S, result);
  const MatrixXd RinvSt = S.transpose() / 0.5;
  const DareResult reduced = solve_dare(A - B * RinvSt, B, Q - S * RinvSt, R);
  EXPECT_LE((result.X - reduced.X).norm(), 1e-13 * result.X.norm());
  EXPECT_LE((result.K - (reduced.K + RinvSt)).norm(), 1e-13 * result.K.norm());
}

TEST(DareErrors, SingularRIsRefusedByName) {  // DAREX 1.1: R = 0
  const MatrixXd A = (MatrixXd(2, 2) << 2, -1, 1, 0).finished();
  const MatrixXd B = (MatrixXd(2, 1) << 1, 0).finished();
  const MatrixXd Q = (MatrixXd(2, 2) << 0, 0, 0, 1).finished();
  EXPECT_THAT(error_message([&] { solve_dare(A, B, Q, scalar(0.0)); }),
              HasSubstr("DARE: R is singular to working precision"));
}

TEST(DareErrors, UnstabilizablePairIsNamed) {
  const MatrixXd A = (MatrixXd(2, 2) << 2, 0, 0, 0.5).finished();
  const MatrixXd B = (MatrixXd(2, 1) << 0, 1).finished();
  EXPECT_THAT(error_message([&] { solve_dare(A, B, MatrixXd::Identity(2, 2), scalar(1.0)); }),
              HasSubstr("DARE: the pair (A, B) is not stabilizable: the mode λ = 2+0i of A is not controllable"));
}

// A rotation (eigenvalues ±i on the unit circle) that Q does not see.
TEST(DareErrors, ModeOnTheUnitCircleUnseenByQIsNamed) {
  const MatrixXd A = (MatrixXd(3, 3) << 0, 1, 0, -1, 0, 0, 0, 0, 0.5).finished();
  const MatrixXd B = (MatrixXd(3, 1) << 0, 1, 1).finished();
  const MatrixXd Q = Eigen::Vector3d(0, 0, 1).asDiagonal();
  EXPECT_THAT(error_message([&] { solve_dare(A, B, Q, scalar(1.0)); }),
              HasSubstr("(Q, A) is not detectable: the mode λ = "));
  EXPECT_THAT(error_message([&] { solve_dare(A, B, Q, scalar(1.0)); }), HasSubstr("on the unit circle"));
}

// x² + (0.75 − q)x − q = 0 has no real root for q = −0.5 or −1 (the closed form above with a = 0.5,
// b = r = 1): the symplectic pencil's eigenvalues lie on the unit circle, (A, B) and Q are not to
// blame, and the doubling either breaks down or does not converge.
TEST(DareErrors, PencilEigenvaluesOnTheUnitCircle) {
  EXPECT_THAT(error_message([] { solve_dare(scalar(0.5), scalar(1.0), scalar(-0.5), scalar(1.0)); }),
              HasSubstr("DARE: the doubling did not converge in 64 steps"));
  for (const double q : {-0.5, -1.0})
    EXPECT_THAT(error_message([q] { solve_dare(scalar(0.5), scalar(1.0), scalar(q), scalar(1.0)); }),
                HasSubstr("the symplectic pencil has eigenvalues on the unit circle"));
}

TEST(DareErrors, IndefiniteCurvatureIsRefused) {
  EXPECT_THAT(error_message([] { solve_dare(scalar(0.5), scalar(0.1), scalar(0.0), scalar(-1.0)); }),
              HasSubstr("DARE: R + B'XB is not positive definite at the solution (min eigenvalue -1"));
}

TEST(DareErrors, InputsAreChecked) {
  const MatrixXd I = MatrixXd::Identity(2, 2);
  EXPECT_THAT(error_message([&] { solve_dare(I, I, I, I, MatrixXd::Zero(2, 1)); }),
              HasSubstr("DARE: S is 2x1 but B is 2x2"));
  EXPECT_THAT(error_message([&] { solve_dare(I, I, (MatrixXd(2, 2) << 1, 1, 0, 1).finished(), I); }),
              HasSubstr("DARE: Q is not symmetric"));
  EXPECT_THAT(error_message([&] { solve_dare(I, I, I, scalar(1.0)); }), HasSubstr("DARE: R is 1x1 but B has 2 columns"));
  MatrixXd A = I;
  A(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_message([&] { solve_dare(A, I, I, I); }), HasSubstr("DARE: A has a non-finite entry"));
}

}  // namespace
}  // namespace thetad
