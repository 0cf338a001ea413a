// The second shipped plant, the RTAC/TORA benchmark: its SDC factorization is exact, its Jacobian
// is f's, and it loses stabilizability exactly where the header says.
#include "core/tora_plant.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tests/central_differences.hpp"
#include "tests/error_message.hpp"
#include "tests/linear_algebra.hpp"

namespace thetad {
namespace {

Eigen::VectorXd random_state(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(-3.0, 3.0);
  return Eigen::Vector4d(uniform(rng), uniform(rng), 2.0 * uniform(rng), uniform(rng));
}

TEST(ToraPlant, TheSdcFactorizationIsExact) {
  const ToraPlant plant;
  std::mt19937_64 rng(7);
  for (int i = 0; i < 200; ++i) {
    const Eigen::VectorXd x = random_state(rng);
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, 2.0 * std::uniform_real_distribution<double>(-1, 1)(rng));
    const auto [F, B] = plant.sdc(x, u);
    const Eigen::VectorXd f = plant.f(x, u);
    EXPECT_LT((F * x + B * u - f).norm(), 1e-13 * (1.0 + f.norm())) << x.transpose();
  }
}

TEST(ToraPlant, TheJacobianIsTheDerivativeOfF) {
  const ToraPlant plant(0.5);
  std::mt19937_64 rng(11);
  for (int i = 0; i < 50; ++i) {
    const Eigen::VectorXd x = random_state(rng);
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, 0.7);
    Eigen::MatrixXd dfdx(4, 4), dfdu(4, 1);
    ASSERT_TRUE(plant.jacobian(x, u, dfdx, dfdu));
    const Eigen::MatrixXd by_x = testing::central_differences([&](const Eigen::VectorXd& z) { return plant.f(z, u); }, x);
    const Eigen::MatrixXd by_u = testing::central_differences([&](const Eigen::VectorXd& z) { return plant.f(x, z); }, u);
    EXPECT_LT(testing::row_relative_error(dfdx, by_x), 1e-8) << x.transpose();
    EXPECT_LT(testing::row_relative_error(dfdu, by_u), 1e-8) << x.transpose();
  }
}

// The smallest singular value of [F − λI, B] over the eigenvalues λ of F (the PBH test): zero for
// a mode the input cannot reach.
double pbh_margin(const ToraPlant& plant, const Eigen::Vector4d& x) {
  const auto [F, B] = plant.sdc(x, Eigen::VectorXd::Zero(1));
  double smallest = 1e300;
  const Eigen::VectorXcd eigenvalues = testing::eigenvalues_of(F);
  for (const std::complex<double>& lambda : eigenvalues) {
    Eigen::MatrixXcd pencil(4, 5);
    pencil.leftCols(4) = F.cast<std::complex<double>>() - lambda * Eigen::MatrixXcd::Identity(4, 4);
    pencil.rightCols(1) = B.cast<std::complex<double>>();
    smallest = std::min(smallest, testing::singular_values_of(pencil).minCoeff());
  }
  return smallest;
}

TEST(ToraPlant, LosesStabilizabilityWhereTheRotorIsAcrossAndStill) {
  const ToraPlant plant;
  const double across = std::numbers::pi / 2;
  EXPECT_LT(pbh_margin(plant, Eigen::Vector4d(0.3, -0.2, across, 0.0)), 1e-12);
  EXPECT_LT(pbh_margin(plant, Eigen::Vector4d(1.0, 0.5, -across, 0.0)), 1e-12);
  // Anywhere else the pair reaches every mode: at rest, with the rotor turning, or not across.
  EXPECT_GT(pbh_margin(plant, Eigen::Vector4d(1.0, 0.0, 0.0, 0.0)), 1e-3);
  EXPECT_GT(pbh_margin(plant, Eigen::Vector4d(0.3, -0.2, across, 0.5)), 1e-3);
  EXPECT_GT(pbh_margin(plant, Eigen::Vector4d(0.3, -0.2, 1.2, 0.0)), 1e-3);
}

TEST(ToraPlant, NamesItsSignalsAndRefusesACouplingOutsideTheUnitInterval) {
  const ToraPlant plant;
  EXPECT_EQ(plant.state_columns()[2].header(), "theta_rad");
  EXPECT_EQ(plant.input_columns()[0].header(), "torque");
  for (double epsilon : {0.0, 1.0, -0.1, std::nan("")})
    EXPECT_THAT(testing::error_message([&] { ToraPlant bad(epsilon); }), ::testing::HasSubstr("epsilon must lie in (0, 1)"));
}

}  // namespace
}  // namespace thetad
