// solve_care's refusals: every precondition of a stabilizing solution that the data break gives a
// thetad::Error that names it (and the measured quantity), never a P.
#include "core/riccati.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <limits>

#include "core/error.hpp"
#include "tests/core/care_checks.hpp"
#include "tests/error_message.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::error_message;
using testing::scalar;


TEST(SolveCareErrors, DimensionMismatch) {
  const MatrixXd I2 = MatrixXd::Identity(2, 2);
  EXPECT_THAT(error_message([&] { solve_care(MatrixXd::Zero(2, 3), I2, I2, I2); }), HasSubstr("A must be square"));
  EXPECT_THAT(error_message([&] { solve_care(I2, MatrixXd::Zero(3, 1), I2, scalar(1)); }),
              HasSubstr("B is 3x1 but A is 2x2"));
  EXPECT_THAT(error_message([&] { solve_care(I2, MatrixXd::Zero(2, 1), MatrixXd::Identity(3, 3), scalar(1)); }),
              HasSubstr("Q is 3x3 but A is 2x2"));
  EXPECT_THAT(error_message([&] { solve_care(I2, MatrixXd::Zero(2, 1), I2, I2); }),
              HasSubstr("R is 2x2 but B has 1 columns"));
  EXPECT_THAT(error_message([&] { solve_care(MatrixXd(0, 0), MatrixXd(0, 1), MatrixXd(0, 0), scalar(1)); }),
              HasSubstr("A must be square and non-empty"));
}

TEST(SolveCareErrors, NonFiniteEntries) {
  const MatrixXd I2 = MatrixXd::Identity(2, 2);
  MatrixXd bad = I2;
  bad(1, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_message([&] { solve_care(bad, I2, I2, I2); }), HasSubstr("A has a non-finite entry"));
  bad(1, 0) = std::numeric_limits<double>::infinity();
  EXPECT_THAT(error_message([&] { solve_care(I2, bad, I2, I2); }), HasSubstr("B has a non-finite entry"));
  EXPECT_THAT(error_message([&] { solve_care(I2, I2, bad, I2); }), HasSubstr("Q has a non-finite entry"));
  EXPECT_THAT(error_message([&] { solve_care(I2, I2, I2, bad); }), HasSubstr("R has a non-finite entry"));
}

TEST(SolveCareErrors, BadWeights) {
  const MatrixXd I2 = MatrixXd::Identity(2, 2);
  MatrixXd asymmetric = I2;
  asymmetric(0, 1) = 0.5;
  EXPECT_THAT(error_message([&] { solve_care(I2, I2, asymmetric, I2); }), HasSubstr("Q is not symmetric"));
  EXPECT_THAT(error_message([&] { solve_care(I2, I2, I2, asymmetric); }), HasSubstr("R is not symmetric"));
  MatrixXd indefinite(2, 2);
  indefinite << 1, 0, 0, -2;
  EXPECT_THAT(error_message([&] { solve_care(I2, I2, indefinite, I2); }),
              HasSubstr("Q is not positive semi-definite (min eigenvalue -2"));
  EXPECT_THAT(error_message([&] { solve_care(I2, I2, I2, indefinite); }),
              HasSubstr("R is not symmetric positive definite (min eigenvalue -2"));
  MatrixXd singular(2, 2);
  singular << 1, 1, 1, 1;
  EXPECT_THAT(error_message([&] { solve_care(I2, I2, I2, singular); }),
              HasSubstr("R is not symmetric positive definite"));
}

TEST(SolveCareErrors, ImaginaryAxisEigenvalues) {
  // A = 0 with no input: the Hamiltonian [[0, 0], [−1, 0]] has λ = 0 twice.
  EXPECT_THAT(error_message([&] { solve_care(scalar(0), scalar(0), scalar(1), scalar(1)); }),
              AllOf(HasSubstr("eigenvalues on the imaginary axis (|Re λ| = 0"),
                    HasSubstr("the pair (A, B) is not stabilizable: the mode λ = 0+0i of A is not controllable")));
  // Undamped oscillator that Q does not see: unobservable modes ±i on the axis.
  MatrixXd A(2, 2);
  A << 0, 1, -1, 0;
  MatrixXd B(2, 1);
  B << 0, 1;
  EXPECT_THAT(error_message([&] { solve_care(A, B, MatrixXd::Zero(2, 2), scalar(1)); }),
              AllOf(HasSubstr("imaginary axis"), HasSubstr("(Q, A) is not detectable: the mode λ = 0"),
                    HasSubstr("i of A on the imaginary axis is not seen by Q")));
}

TEST(SolveCareErrors, MatrixSignRefusesWhatItCannotSolve) {
  // Undamped oscillator that Q does not see: the sign iteration meets a singular iterate.
  MatrixXd A(2, 2);
  A << 0, 1, -1, 0;
  MatrixXd B(2, 1);
  B << 0, 1;
  EXPECT_THAT(error_message([&] { solve_care(A, B, MatrixXd::Zero(2, 2), scalar(1), CareMethod::matrix_sign); }),
              AllOf(HasSubstr("matrix sign iteration on the Hamiltonian failed"), HasSubstr("CareMethod::schur says which")));
}

TEST(SolveCareErrors, Unstabilizable) {
  // Unstable mode at +1 that B cannot reach.
  MatrixXd A(2, 2);
  A << 1, 0, 0, -1;
  MatrixXd B(2, 1);
  B << 0, 1;
  EXPECT_THAT(error_message([&] { solve_care(A, B, MatrixXd::Identity(2, 2), scalar(1)); }),
              AllOf(HasSubstr("no stabilizing solution"), HasSubstr("rcond(U1) = "),
                    HasSubstr("the pair (A, B) is not stabilizable: the mode λ = 1+0i of A is not controllable")));
}

// The unstabilizable pair that once came back as a P holding Inf (issue 16): every method refuses
// it, naming the mode, as MATLAB care, SLICOT and Drake do.
TEST(SolveCareErrors, UnstabilizableUnstableModeIsRefusedByEveryMethod) {
  MatrixXd A = Eigen::Vector2d(1.0, 2.0).asDiagonal();
  MatrixXd B(2, 1);
  B << 1, 0;
  for (const CareMethod method : {CareMethod::automatic, CareMethod::matrix_sign, CareMethod::schur}) {
    EXPECT_THAT(error_message([&] { solve_care(A, B, MatrixXd::Identity(2, 2), scalar(1), method); }),
                HasSubstr("the pair (A, B) is not stabilizable: the mode λ = 2+0i of A is not controllable "
                          "(σ_min[A − λI, B] = 0, B scaled to ‖A‖_F)"));
  }
}

}  // namespace
}  // namespace thetad
