// J_dev (docs/model.md §7.2): zero on the commanded motion flown exactly at its trim, whatever
// input holds the trim; ½ q δ² T_c for a deviation δ of one state (a yaw rate); (u − u_r)
// weighed, not u.
#include "core/sim/deviation_cost.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "core/trim_table.hpp"

namespace thetad::sim {
namespace {

using namespace heli;

class DeviationCostTest : public ::testing::Test {
 protected:
  DeviationCostTest()
      : table_(std::make_shared<TrimTable>(model_, TrimGridAxes{{0.0, 1.0}, {0.0}, {0.0}, 3.5})) {
    weights_.state = Eigen::VectorXd::Ones(kStateDim);
    weights_.state[kS] = 0.0;
    weights_.input = Eigen::VectorXd::Constant(kInputDim, 2.0);
    weights_.name = "test";
    // Forward at 1 m/s, on the command, at the table's trim there (a grid point).
    reference_.position = Eigen::Vector3d(4.0, -1.0, -3.5);
    reference_.velocity = Eigen::Vector3d(1.0, 0.0, 0.0);
    reference_.integral = Eigen::Vector3d(0.3, -0.2, 1.0);
    trim_ = {Eigen::VectorXd(kStateDim), Eigen::VectorXd(kInputDim), Eigen::VectorXd(kStateDim)};
    table_->trim(reference_, trim_);
    state_ = trim_.state;
    state_.segment<3>(kXp) = reference_.position;
    state_.segment<3>(kXi) = reference_.integral;
    state_[kS] = 1.0;
  }

  // One sample's J_dev with the true tracking vector of `x` (integral errors: x's less the command's).
  double one_sample(const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
    DeviationCost cost(model_, table_, weights_, 0.01);
    Eigen::VectorXd v(kStateDim);
    model_.true_tracking_vector(x, reference_, x.segment<3>(kXi) - reference_.integral, v);
    cost.add(x, reference_, v, u);
    return cost.value();
  }

  const Helicopter model_;
  std::shared_ptr<const TrimTable> table_;
  TrimPoint trim_;
  DeviationWeights weights_;
  Reference reference_;
  Eigen::VectorXd state_;
};

TEST_F(DeviationCostTest, IsZeroOnTheCommandedMotionAtItsTrim) {
  EXPECT_LE(one_sample(state_, trim_.input), 1e-20);
}

TEST_F(DeviationCostTest, WeighsTheDeviationOfAStateAndOfTheInputFromTheTrims) {
  Eigen::VectorXd x = state_;
  x[kR] += 0.1;
  EXPECT_NEAR(one_sample(x, trim_.input), 0.5 * 0.1 * 0.1 * 0.01, 1e-15);
  Eigen::VectorXd u = trim_.input;
  u[kTmr] += 3.0;
  EXPECT_NEAR(one_sample(state_, u), 0.5 * 2.0 * 9.0 * 0.01, 1e-12);
}

}  // namespace
}  // namespace thetad::sim
