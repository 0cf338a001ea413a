// The shooting interval's exact derivatives against central differences of its own map on the
// helicopter (random nodes and inputs), priced as J and as J_dev; optimal_control_test checks them
// on the linear plant.
#include "optimal/shooting_interval.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/helicopter/helicopter.hpp"
#include "core/helicopter/paper_weights.hpp"
#include "experiment/flight.hpp"
#include "tests/optimal/interval_differences.hpp"
#include "tests/error_message.hpp"

namespace thetad {
namespace {

const FixedPosition kHoldAtOrigin(Eigen::Vector3d::Zero());

// The exact block of interval k at (node, u) against central differences of the interval map.
double derivative_error(ShootingInterval& interval, int k, const Eigen::VectorXd& node, const Eigen::VectorXd& u) {
  Eigen::VectorXd next(node.size());
  Eigen::MatrixXd derivative;
  interval.linearize(k, node, u, next, derivative);
  Eigen::VectorXd z(node.size() + u.size());
  z << node, u;
  return testing::row_relative_error(derivative, testing::interval_differences(interval, k, z, node.size()));
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
    worst = std::max(worst, derivative_error(interval, trial % 2, node, u));
  }
  EXPECT_LT(worst, 1e-8);  // measured 2.2e-10
}

// Priced as J_dev in the hover-to-hover move (1 m/s north at t = 1.5 s): V* depends on the node's
// attitude through the commanded body velocity, and its derivative, by differences inside, still
// matches differences of the whole map.
TEST(ShootingInterval, JDevDerivativesAreCentralDifferences) {
  RunControls controls;
  controls.duration = 3.0;
  controls.ideal = true;
  const Flight flight("hover-to-hover", controls);
  std::string why_not;
  const std::optional<sim::DeviationCost> deviation = flight.deviation_cost(why_not);
  ASSERT_TRUE(deviation) << why_not;
  OptimalControlProblem problem;
  problem.plant = &flight.model();
  problem.reference = &flight.scenario().trajectory;
  problem.initial_state = flight.initial_state();
  problem.first_sample = 1500;
  problem.state_weights = deviation->weights().state;
  problem.input_weights = deviation->weights().input;
  problem.deviation_trims = deviation->trims();
  problem.interval_periods = 10;
  problem.intervals = 2;
  problem.sampled_position_integral = heli::kXi;
  ASSERT_GT(problem.reference->velocity(1.5).norm(), 0.5);
  ShootingInterval interval(problem);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::VectorXd node = Eigen::VectorXd::Zero(problem.node_dim());
    node.head(heli::kStateDim) = problem.initial_state;
    node[heli::kXp] = 2.0 + unit(rng);
    node[heli::kU] = 1.0 + 0.5 * unit(rng);
    for (int i = heli::kPhi; i <= heli::kB1; ++i) node[i] = 0.2 * unit(rng);
    node.tail<3>() = 0.3 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    Eigen::VectorXd u(heli::kInputDim);
    u << 80.0 + 10.0 * unit(rng), 0.1 * unit(rng), 0.05 * unit(rng), 0.03 * unit(rng), 0.03 * unit(rng);
    worst = std::max(worst, derivative_error(interval, trial % 2, node, u));
  }
  EXPECT_LT(worst, 1e-7);
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
  problem.reference = &kHoldAtOrigin;
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
