// The helicopter's exact Jacobian (automatic differentiation, the rotor speed by the
// implicit-function theorem) against central differences of f.
#include <gtest/gtest.h>

#include <random>

#include "core/error.hpp"
#include "core/helicopter/helicopter.hpp"
#include "tests/central_differences.hpp"
#include "tests/core/helicopter_fixtures.hpp"

namespace thetad::heli {
namespace {

using namespace testing;
using thetad::testing::central_differences;
using thetad::testing::row_relative_error;

// [df/dx df/du] both ways: exactly, and by central differences of f over z = (x, u) with the step
// h max(1, |z_j|). The differences' error is O(h^2) plus the rotor speed's root tolerance (1e-12
// relative) over h: about 3e-8 of a row's largest entry with the rotor speed, 1e-9 without.
double jacobian_error(const Helicopter& heli, const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                      double h = std::cbrt(std::numeric_limits<double>::epsilon())) {
  Eigen::MatrixXd dfdx(kStateDim, kStateDim), dfdu(kStateDim, kInputDim);
  EXPECT_TRUE(heli.jacobian(x, u, dfdx, dfdu));
  Eigen::MatrixXd exact(kStateDim, kStateDim + kInputDim);
  exact << dfdx, dfdu;
  EXPECT_TRUE(exact.allFinite());
  Eigen::VectorXd z(kStateDim + kInputDim);
  z << x, u;
  const auto f = [&](const Eigen::VectorXd& at) { return heli.f(at.head(kStateDim), at.tail(kInputDim)); };
  return row_relative_error(exact, central_differences(f, z, h));
}

TEST(HelicopterJacobian, EqualsCentralDifferencesOnRandomStatesAllOptionSets) {
  for (const auto& [name, options] : option_sets()) {
    Helicopter heli(kNominal, options);
    std::mt19937_64 rng(7);
    double worst = 0.0;
    for (int trial = 0; trial < 200; ++trial) {
      heli.set_environment(trial % 2 == 0 ? Environment{} : random_environment(rng));
      const Eigen::VectorXd x = random_state(rng), u = random_input(rng);
      worst = std::max(worst, jacobian_error(heli, x, u));
    }
    EXPECT_LT(worst, 1e-7) << name;
  }
}

// In hover the air is still in the rotor plane and at the tail (u = v = 0), where the airspeed
// norms have no derivative; the Jacobian is finite there and matches the differences all the same.
TEST(HelicopterJacobian, FiniteAndRightInStillAirHover) {
  const Helicopter heli(kNominal);
  Eigen::VectorXd x = rest_state(), u = Eigen::VectorXd::Zero(kInputDim);
  x[kZp] = -3.5;
  u[kTmr] = kNominal.mass * kNominal.gravity;
  EXPECT_LT(jacobian_error(heli, x, u, 1e-6), 1e-7);
}

TEST(HelicopterJacobian, RefusesMisSizedOutputs) {
  const Helicopter heli(kNominal);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(kInputDim);
  u[kTmr] = 80.0;
  Eigen::MatrixXd dfdx(kStateDim, kStateDim), dfdu(kStateDim, kInputDim + 1);
  EXPECT_THROW(heli.jacobian(rest_state(), u, dfdx, dfdu), Error);
}

}  // namespace
}  // namespace thetad::heli
