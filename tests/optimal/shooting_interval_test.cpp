// The shooting interval's exact derivatives against central differences of its own map, on the
// linear test plant and on the helicopter (random nodes and inputs), and against the exact
// discrete map on the linear plant.
#include "optimal/shooting_interval.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/helicopter/helicopter.hpp"
#include "core/helicopter/paper_weights.hpp"
#include "tests/error_message.hpp"
#include "tests/test_plants.hpp"

namespace thetad {
namespace {

const FixedPosition kOrigin(Eigen::Vector3d::Zero());

// d(next node, cost)/d(node, u) by central differences of propagate(), step h max(1, |z_j|).
Eigen::MatrixXd central_differences(ShootingInterval& interval, int k, const Eigen::VectorXd& node,
                                    const Eigen::VectorXd& u) {
  const double h = std::cbrt(std::numeric_limits<double>::epsilon());
  const Eigen::Index d = node.size(), m = u.size();
  Eigen::MatrixXd derivative(d + 1, d + m);
  Eigen::VectorXd plus(d), minus(d);
  for (Eigen::Index j = 0; j < d + m; ++j) {
    Eigen::VectorXd node_plus = node, node_minus = node, u_plus = u, u_minus = u;
    double& up = j < d ? node_plus[j] : u_plus[j - d];
    double& down = j < d ? node_minus[j] : u_minus[j - d];
    const double step = h * std::max(1.0, std::abs(up));
    up += step;
    down -= step;
    const double cost_plus = interval.propagate(k, node_plus, u_plus, plus);
    const double cost_minus = interval.propagate(k, node_minus, u_minus, minus);
    derivative.col(j).head(d) = (plus - minus) / (up - down);
    derivative(d, j) = (cost_plus - cost_minus) / (up - down);
  }
  return derivative;
}

// The largest difference, relative to the largest entry of its row (rows differ in scale by orders
// of magnitude on the helicopter).
double row_relative_error(const Eigen::MatrixXd& exact, const Eigen::MatrixXd& differences) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < exact.rows(); ++i) {
    const double scale = std::max(1e-12, differences.row(i).cwiseAbs().maxCoeff());
    worst = std::max(worst, (exact.row(i) - differences.row(i)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

LinearPlant small_plant() {
  Eigen::MatrixXd A(3, 3), B(3, 2);
  A << 0.2, 1.0, 0.0, -1.0, -0.3, 0.5, 0.1, 0.0, -0.8;
  B << 0.0, 0.3, 1.0, 0.0, 0.2, 1.0;
  return {A, B};
}

TEST(ShootingInterval, LinearPlantDerivativesAreCentralDifferencesAndTheDiscreteMap) {
  const LinearPlant plant = small_plant();
  OptimalControlProblem problem;
  problem.plant = &plant;
  problem.reference = &kOrigin;
  problem.initial_state = Eigen::Vector3d(1.0, -0.5, 0.8);
  problem.state_weights = Eigen::Vector3d(2.0, 1.0, 0.5);
  problem.input_weights = Eigen::Vector2d(0.3, 1.5);
  problem.dt = 0.01;
  problem.controller_period_steps = 2;
  problem.interval_periods = 3;
  problem.intervals = 6;
  ShootingInterval interval(problem);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd node = Eigen::VectorXd::NullaryExpr(3, [&] { return normal(rng); });
    const Eigen::VectorXd u = Eigen::VectorXd::NullaryExpr(2, [&] { return normal(rng); });
    Eigen::VectorXd next(3), reached(3);
    Eigen::MatrixXd derivative;
    const int k = trial % problem.intervals;
    const double cost = interval.linearize(k, node, u, next, derivative);
    EXPECT_EQ(cost, interval.propagate(k, node, u, reached));
    EXPECT_EQ(next, reached);
    EXPECT_LT(row_relative_error(derivative, central_differences(interval, k, node, u)), 1e-9);
    // The map is x+ = Φ x + Γ u: its derivative is [Φ Γ] whatever the point.
    Eigen::MatrixXd Phi(3, 3), Gamma(3, 2);
    for (int j = 0; j < 3; ++j) Phi.col(j) = (interval.propagate(k, Eigen::VectorXd::Unit(3, j), Eigen::VectorXd::Zero(2), reached), reached);
    for (int j = 0; j < 2; ++j) Gamma.col(j) = (interval.propagate(k, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Unit(2, j), reached), reached);
    EXPECT_LE((derivative.topLeftCorner(3, 3) - Phi).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LE((derivative.topRightCorner(3, 2) - Gamma).cwiseAbs().maxCoeff(), 1e-14);
  }
}

// On the helicopter, priced as simulate() prices J (the sampled integral in the node), around
// hover at random states and inputs, in a forward-flight reference.
TEST(ShootingInterval, HelicopterDerivativesAreCentralDifferences) {
  const heli::Helicopter plant;
  const FixedPosition reference(Eigen::Vector3d(2.0, -1.0, -3.5));
  OptimalControlProblem problem;
  problem.plant = &plant;
  problem.reference = &reference;
  problem.initial_state = Eigen::VectorXd::Zero(heli::kStateDim);
  problem.initial_state[heli::kS] = 1.0;
  problem.state_weights = heli::paper_state_weights();
  problem.input_weights = heli::paper_input_weights();
  problem.controller_period_steps = 1;
  problem.interval_periods = 10;
  problem.intervals = 2;
  problem.sampled_position_integral = heli::kXi;
  ShootingInterval interval(problem);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::VectorXd node = Eigen::VectorXd::Zero(problem.node_dim());
    for (int i = heli::kXp; i <= heli::kZp; ++i) node[i] = 3.0 * unit(rng);
    for (int i = heli::kU; i <= heli::kW; ++i) node[i] = 5.0 * unit(rng);
    for (int i = heli::kPhi; i <= heli::kB1; ++i) node[i] = 0.2 * unit(rng);
    node.segment<3>(heli::kXi) = 2.0 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    node[heli::kS] = 1.0 + 0.2 * unit(rng);
    node.tail<3>() = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    Eigen::VectorXd u(heli::kInputDim);
    u << 80.0 + 10.0 * unit(rng), 0.1 * unit(rng), 0.05 * unit(rng), 0.03 * unit(rng), 0.03 * unit(rng);
    Eigen::VectorXd next(problem.node_dim());
    Eigen::MatrixXd derivative;
    interval.linearize(trial % 2, node, u, next, derivative);
    worst = std::max(worst, row_relative_error(derivative, central_differences(interval, trial % 2, node, u)));
  }
  EXPECT_LT(worst, 1e-8);  // measured 2.2e-10
}

// A plant that gives no Jacobian.
class NoJacobianPlant final : public SdcPlant {
 public:
  int state_dim() const override { return 1; }
  int input_dim() const override { return 1; }
  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override {
    xdot = -x + u;
  }
  void sdc(const Eigen::Ref<const Eigen::VectorXd>&, const Eigen::Ref<const Eigen::VectorXd>&,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override {
    F.setConstant(-1.0);
    B.setConstant(1.0);
  }
};

TEST(ShootingInterval, APlantWithoutJacobianIsRefusedClearly) {
  const NoJacobianPlant plant;
  OptimalControlProblem problem;
  problem.plant = &plant;
  problem.reference = &kOrigin;
  problem.initial_state = Eigen::VectorXd::Ones(1);
  problem.state_weights = problem.input_weights = Eigen::VectorXd::Ones(1);
  ShootingInterval interval(problem);
  Eigen::VectorXd next(1);
  Eigen::MatrixXd derivative;
  EXPECT_NE(testing::error_message([&] {
              interval.linearize(0, interval.initial_node(), Eigen::VectorXd::Zero(1), next, derivative);
            }).find("gives no Jacobian of f (SdcPlant::jacobian)"),
            std::string::npos);
}

}  // namespace
}  // namespace thetad
