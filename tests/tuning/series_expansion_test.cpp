// ThetaDController::series_expansion: the polynomial in e_1 … e_{N−1} that the tuner evaluates
// must reproduce the controller's own series (value_matrix, the code control() flies) for any k, l.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "controllers/theta_d.hpp"
#include "tests/test_plants.hpp"
#include "tests/tuning/helicopter_theta_d.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// e_i(t) for the controller's own k, l at time t.
VectorXd factors(const ThetaDController& c, double t) {
  VectorXd e(c.settings().terms - 1);
  for (Eigen::Index i = 0; i < e.size(); ++i)
    e[i] = perturbation_factor(c.settings().k[i], c.settings().l[i], t - c.start_time());
  return e;
}

double relative_difference(const MatrixXd& a, const MatrixXd& b) { return (a - b).norm() / b.norm(); }

TEST(SeriesExpansion, ThreeTermsHaveThePiecesOfSpec75) {
  const testing::HelicopterThetaD heli;
  ThetaDController controller = heli.make(3);
  const SeriesExpansion expansion = controller.series_expansion(heli.excursion(1.0), heli.hover_input);
  // T0; T1 = e1 T1°; T2 = e2 (T2a + e1 T2b + e1² T2c).
  const std::vector<std::vector<int>> expected{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 1}};
  EXPECT_EQ(expansion.powers, expected);
  EXPECT_EQ((expansion.pieces[0] - controller.T0()).norm(), 0.0);
  for (const MatrixXd& piece : expansion.pieces) EXPECT_EQ((piece - piece.transpose()).norm(), 0.0);
}

TEST(SeriesExpansion, ReproducesTheHelicopterSeriesForRandomKL) {
  const testing::HelicopterThetaD heli;
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> k(0.0, 1.5), l(0.01, 20.0), t(0.0, 3.0), thrust(-20.0, 20.0);
  for (int trial = 0; trial < 12; ++trial) {
    ThetaDController controller = heli.make(3, Eigen::Vector2d(k(random), k(random)), Eigen::Vector2d(l(random), l(random)));
    const double time = t(random);
    const VectorXd x = heli.excursion(1.0 + time);
    VectorXd input = heli.hover_input;
    input[heli::kTmr] += thrust(random);  // F, B follow the rotor speed
    const MatrixXd expanded = controller.series_expansion(x, input).evaluate(factors(controller, time));
    EXPECT_LT(relative_difference(expanded, controller.value_matrix(x, input, time)), 1e-12) << "trial " << trial;
  }
}

// Five terms on a random plant: the general polynomial recursion, not only the N = 3 pieces.
TEST(SeriesExpansion, ReproducesAFiveTermSeriesOnARandomPlant) {
  const RandomSdcPlant plant(6, 2, 7, 0.3);
  ThetaDSettings s;
  s.terms = 5;
  s.k = (VectorXd(4) << 0.9, 1.3, 0.4, 1.1).finished();
  s.l = (VectorXd(4) << 0.7, 3.0, 12.0, 0.05).finished();
  s.Q = VectorXd::LinSpaced(6, 1.0, 3.0).asDiagonal();
  s.R = Eigen::Vector2d(1.0, 2.0).asDiagonal();
  ThetaDController controller(plant, s);
  controller.reset(VectorXd::Constant(6, 0.1), 0.25);
  const VectorXd x = (VectorXd(6) << 0.3, -0.2, 0.4, 0.1, 0.5, -0.4).finished();
  const VectorXd input = Eigen::Vector2d(0.2, -0.1);
  const SeriesExpansion expansion = controller.series_expansion(x, input);
  for (double t : {0.25, 0.4, 1.0, 7.0}) {
    EXPECT_LT(relative_difference(expansion.evaluate(factors(controller, t)), controller.value_matrix(x, input, t)), 1e-12)
        << "t = " << t;
  }
}

}  // namespace
}  // namespace thetad
