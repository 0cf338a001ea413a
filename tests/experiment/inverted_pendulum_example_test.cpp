// The example plant plug-in's plant (experiment/examples/pendulum-plugin): its SDC factorization
// is exact, near the upright too (where sin θ / θ is taken by its series), and its Jacobian is f's.
// The command-line tests fly its plug-in build (apps/plant_plugin_test.cpp).
#include "experiment/examples/pendulum-plugin/inverted_pendulum.hpp"

#include <random>

#include <gtest/gtest.h>

#include "tests/central_differences.hpp"

namespace thetad {
namespace {

using examples::InvertedPendulum;

Eigen::VectorXd pendulum_example_state(std::mt19937_64& rng, double angle_range) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  return Eigen::Vector2d(angle_range * uniform(rng), 4.0 * uniform(rng));
}

TEST(InvertedPendulumExample, TheSdcFactorizationIsExactNearTheUprightAndAwayFromIt) {
  const InvertedPendulum plant(0.7, 0.3);
  std::mt19937_64 rng(5);
  for (const double range : {1e-5, 1e-3, 3.0}) {
    for (int i = 0; i < 100; ++i) {
      const Eigen::VectorXd x = pendulum_example_state(rng, range);
      const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, 2.0 * std::uniform_real_distribution<double>(-1, 1)(rng));
      const auto [F, B] = plant.sdc(x, u);
      const Eigen::VectorXd f = plant.f(x, u);
      EXPECT_LT((F * x + B * u - f).norm(), 1e-14 * (1.0 + f.norm())) << x.transpose();
    }
  }
}

TEST(InvertedPendulumExample, TheJacobianIsTheDerivativeOfF) {
  const InvertedPendulum plant(1.3, 0.1);
  std::mt19937_64 rng(9);
  for (int i = 0; i < 50; ++i) {
    const Eigen::VectorXd x = pendulum_example_state(rng, 3.0);
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, -0.4);
    Eigen::MatrixXd dfdx(2, 2), dfdu(2, 1);
    ASSERT_TRUE(plant.jacobian(x, u, dfdx, dfdu));
    const Eigen::MatrixXd by_x = testing::central_differences([&](const Eigen::VectorXd& z) { return plant.f(z, u); }, x);
    const Eigen::MatrixXd by_u = testing::central_differences([&](const Eigen::VectorXd& z) { return plant.f(x, z); }, u);
    EXPECT_LT(testing::row_relative_error(dfdx, by_x), 1e-8) << x.transpose();
    EXPECT_LT(testing::row_relative_error(dfdu, by_u), 1e-8) << x.transpose();
  }
}

}  // namespace
}  // namespace thetad
