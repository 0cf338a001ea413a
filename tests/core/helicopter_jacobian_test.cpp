#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "core/helicopter/helicopter.hpp"
#include "tests/core/helicopter_fixtures.hpp"

namespace thetad::heli {
namespace {

using namespace testing;

// [df/dx df/du] by central differences with the step h max(1, |z_j|), the yardstick for the
// automatic derivatives: their error is O(h^2) plus the rotor speed's root tolerance (1e-12
// relative) over h, about 3e-8 of a row's largest entry with the rotor speed, 1e-9 without.
Eigen::MatrixXd central_differences(const Helicopter& heli, const Eigen::VectorXd& x, const Eigen::VectorXd& u, double h) {
  Eigen::MatrixXd J(kStateDim, kStateDim + kInputDim);
  for (int j = 0; j < kStateDim + kInputDim; ++j) {
    Eigen::VectorXd xp = x, xm = x, up = u, um = u;
    double& plus = j < kStateDim ? xp[j] : up[j - kStateDim];
    double& minus = j < kStateDim ? xm[j] : um[j - kStateDim];
    const double step = h * std::max(1.0, std::abs(plus));
    plus += step;
    minus -= step;
    J.col(j) = (heli.f(xp, up) - heli.f(xm, um)) / (plus - minus);
  }
  return J;
}

Eigen::MatrixXd automatic(const Helicopter& heli, const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
  Eigen::MatrixXd dfdx(kStateDim, kStateDim), dfdu(kStateDim, kInputDim);
  EXPECT_TRUE(heli.jacobian(x, u, dfdx, dfdu));
  Eigen::MatrixXd J(kStateDim, kStateDim + kInputDim);
  J << dfdx, dfdu;
  return J;
}

TEST(HelicopterJacobian, EqualsCentralDifferencesOnRandomStatesAllOptionSets) {
  for (const auto& [name, options] : option_sets()) {
    Helicopter heli(kNominal, options);
    std::mt19937_64 rng(7);
    double worst = 0.0;
    for (int trial = 0; trial < 200; ++trial) {
      heli.set_environment(trial % 2 == 0 ? Environment{} : random_environment(rng));
      const Eigen::VectorXd x = random_state(rng), u = random_input(rng);
      const Eigen::MatrixXd exact = automatic(heli, x, u);
      const Eigen::MatrixXd differences = central_differences(heli, x, u, std::cbrt(std::numeric_limits<double>::epsilon()));
      // Relative to the row's largest entry: the rows' scales differ by orders of magnitude.
      for (int i = 0; i < kStateDim; ++i) {
        const double scale = std::max(1e-12, differences.row(i).cwiseAbs().maxCoeff());
        worst = std::max(worst, (exact.row(i) - differences.row(i)).cwiseAbs().maxCoeff() / scale);
      }
    }
    EXPECT_LT(worst, 1e-7) << name;
  }
}

// In hover the air is still in the rotor plane (u = v = 0), where the advance ratio's norm has no
// derivative; the Jacobian is finite there and matches the differences all the same.
TEST(HelicopterJacobian, FiniteAndRightInStillAirHover) {
  const Helicopter heli(kNominal);
  Eigen::VectorXd x = rest_state(), u = Eigen::VectorXd::Zero(kInputDim);
  x[kZp] = -3.5;
  u[kTmr] = kNominal.mass * kNominal.gravity;
  const Eigen::MatrixXd exact = automatic(heli, x, u);
  ASSERT_TRUE(exact.allFinite());
  const Eigen::MatrixXd differences = central_differences(heli, x, u, 1e-6);
  for (int i = 0; i < kStateDim; ++i) {
    const double scale = std::max(1e-12, differences.row(i).cwiseAbs().maxCoeff());
    EXPECT_LT((exact.row(i) - differences.row(i)).cwiseAbs().maxCoeff() / scale, 1e-7) << "row " << i;
  }
}

TEST(HelicopterJacobian, RefusesMisSizedOutputs) {
  const Helicopter heli(kNominal);
  Eigen::VectorXd x = rest_state(), u = Eigen::VectorXd::Zero(kInputDim);
  u[kTmr] = 80.0;
  Eigen::MatrixXd dfdx(kStateDim, kStateDim), dfdu(kStateDim, kInputDim + 1);
  EXPECT_THROW(heli.jacobian(x, u, dfdx, dfdu), Error);
}

}  // namespace
}  // namespace thetad::heli
