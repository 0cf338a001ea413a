// The diagnosis behind a failed CARE solve at every scale of the weights: stabilizability and
// detectability do not change when Q, R or B is multiplied by a positive number, so neither may
// the diagnosis, from 1e-170 to 1e200 (issue 34, item 6).
#include "core/care_diagnosis.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "core/riccati.hpp"
#include "tests/core/care_checks.hpp"
#include "tests/error_message.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using ::testing::HasSubstr;
using testing::error_message;

constexpr double kScales[] = {1e-170, 1e-100, 1e-10, 1.0, 1e10, 1e100, 1e200};

// The double integrator, reached through its force and weighted on both states: well posed.
struct WellPosed {
  MatrixXd A = (MatrixXd(2, 2) << 0, 1, 0, 0).finished();
  MatrixXd B = (MatrixXd(2, 1) << 0, 1).finished();
  MatrixXd Q = MatrixXd::Identity(2, 2);
};

// An undamped oscillator that Q does not see beside a stable mode that it does: Q ≠ 0, yet the
// modes ±i on the axis are unobserved.
struct Undetectable {
  MatrixXd A = (MatrixXd(3, 3) << 0, 1, 0, -1, 0, 0, 0, 0, -1).finished();
  MatrixXd B = (MatrixXd(3, 1) << 0, 1, 1).finished();
  MatrixXd Q = Eigen::Vector3d(0, 0, 1).asDiagonal();
};

// An unstable mode at +1 that B cannot reach.
struct Unstabilizable {
  MatrixXd A = Eigen::Vector2d(1, -1).asDiagonal();
  MatrixXd B = (MatrixXd(2, 1) << 0, 1).finished();
  MatrixXd Q = MatrixXd::Identity(2, 2);
};

TEST(CareDiagnosis, AWellPosedProblemIsNotMisdiagnosedAtAnyScaleOfQOrB) {
  const WellPosed p;
  for (const double q : kScales) {
    for (const double b : kScales) {
      EXPECT_EQ(broken_care_precondition(p.A, b * p.B, q * p.Q), "") << "Q scaled by " << q << ", B by " << b;
    }
  }
}

TEST(CareDiagnosis, BrokenPreconditionsAreNamedAtEveryScaleOfQOrB) {
  const Undetectable blind;
  const Unstabilizable unreachable;
  for (const double q : kScales) {
    for (const double b : kScales) {
      EXPECT_THAT(broken_care_precondition(blind.A, b * blind.B, q * blind.Q),
                  HasSubstr("(Q, A) is not detectable: the mode λ = "))
          << "Q scaled by " << q << ", B by " << b;
      EXPECT_THAT(broken_care_precondition(unreachable.A, b * unreachable.B, q * unreachable.Q),
                  HasSubstr("the pair (A, B) is not stabilizable: the mode λ = 1+0i of A is not controllable"))
          << "Q scaled by " << q << ", B by " << b;
    }
  }
}

// The same through the solvers, weights (Q and R together, and Q alone) scaled: the failed solve
// names the precondition, not the other one.
TEST(CareDiagnosis, AFailedSolveWithScaledWeightsNamesTheRightPrecondition) {
  const Undetectable blind;
  const Unstabilizable unreachable;
  for (const double c : kScales) {
    for (const double r : {c, 1.0}) {
      for (const CareMethod method : {CareMethod::automatic, CareMethod::schur}) {
        EXPECT_THAT(error_message([&] { solve_care(blind.A, blind.B, c * blind.Q, testing::scalar(r), method); }),
                    HasSubstr("(Q, A) is not detectable: the mode λ = "))
            << "Q scaled by " << c << ", R = " << r;
        EXPECT_THAT(
            error_message([&] { solve_care(unreachable.A, unreachable.B, c * unreachable.Q, testing::scalar(r), method); }),
            HasSubstr("the pair (A, B) is not stabilizable: the mode λ = 1+0i"))
            << "Q scaled by " << c << ", R = " << r;
      }
    }
  }
}

}  // namespace
}  // namespace thetad
