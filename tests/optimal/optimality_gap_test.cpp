// The optimality gap on the helicopter, over a short horizon of the shipped hover-to-hover move:
// the optimum Ipopt finds costs no more than any built-in controller's flight, and the
// transcription prices a flight exactly as the simulator does.
#include "optimal/optimality_gap.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/helicopter/state.hpp"
#include "optimal/shooting_interval.hpp"
#include "tests/error_message.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;

RunControls short_ideal(double horizon) {
  RunControls controls;
  controls.duration = horizon;
  controls.ideal = true;
  controls.timing = false;
  return controls;
}

std::vector<PreparedController> built_in(const Flight& flight) {
  std::vector<PreparedController> controllers;
  for (const char* name : {"theta-d", "sdre", "lqr", "lqr-scheduled"})
    controllers.push_back(flight.prepare(parse_controller_spec(name)));
  return controllers;
}

TEST(OptimalityGap, TheOptimumCostsNoMoreThanAnyControllerOnTheHelicopter) {
  const Flight flight("hover-to-hover", short_ideal(0.5));
  std::vector<PreparedController> controllers = built_in(flight);
  OptimalityOptions options;
  options.control_interval = 0.05;
  const OptimalityGap gap = optimality_gap(flight, controllers, options);
  ASSERT_EQ(gap.optima.size(), 1u);
  const OptimalControlSolution& solution = gap.optima[0].solution;
  ASSERT_TRUE(solution.outcome.converged) << solution.outcome.status;
  EXPECT_EQ(solution.outcome.status, "Solve_Succeeded");
  EXPECT_LE(solution.constraint_violation, 1e-8);
  ASSERT_EQ(gap.flights.size(), 4u);
  for (std::size_t i = 0; i < gap.flights.size(); ++i) {
    const RunResult& run = gap.flights[i];
    ASSERT_TRUE(run.completed()) << run.spec.label << ": " << run.summary.reason;
    EXPECT_EQ(gap.optimum_for(i), &gap.optima[0]);
    EXPECT_EQ(gap.costs[i], run.summary.cost);
    EXPECT_LE(solution.cost, run.summary.cost) << run.spec.label;
    EXPECT_GE(gap.gap_percent(i), 0.0) << run.spec.label;
  }
  // The optimum as a run: the run metrics price its log as the transcription priced it.
  const RunResult& optimum = gap.optima[0].run;
  EXPECT_NEAR(optimum.summary.cost, solution.cost, 1e-12 * solution.cost);
  EXPECT_EQ(optimum.log.rows(), 500);
  EXPECT_TRUE(optimum.completed());
}

// From mid-flight every controller is in its own state: each gets the optimum from there, which
// costs no more than its own flight over the segment, and whose first sample is that state.
TEST(OptimalityGap, FromMidFlightEachControllerHasTheOptimumFromItsOwnState) {
  const Flight flight("hover-to-hover", short_ideal(0.6));
  std::vector<PreparedController> controllers;
  for (const char* name : {"lqr", "lqr-scheduled"}) controllers.push_back(flight.prepare(parse_controller_spec(name)));
  OptimalityOptions options;
  options.start = 0.3;
  const OptimalityGap gap = optimality_gap(flight, controllers, options);
  ASSERT_EQ(gap.optima.size(), 2u);
  for (std::size_t i = 0; i < gap.flights.size(); ++i) {
    const RunResult& run = gap.flights[i];
    ASSERT_TRUE(run.completed()) << run.spec.label;
    const SegmentOptimum* optimum = gap.optimum_for(i);
    ASSERT_NE(optimum, nullptr);
    EXPECT_EQ(optimum->from, run.spec.label);
    EXPECT_EQ(optimum->run.spec.label, "optimal-from-" + run.spec.label);
    ASSERT_TRUE(optimum->solution.outcome.converged) << optimum->solution.outcome.status;
    EXPECT_EQ(optimum->problem.first_sample, 300);
    EXPECT_EQ(optimum->run.log.rows(), 300);
    EXPECT_DOUBLE_EQ(optimum->run.log.row(0)(0), 0.3);
    EXPECT_EQ(optimum->run.log.row(0).segment(4, heli::kStateDim), run.log.row(300).segment(4, heli::kStateDim));
    // The segment is the later part of the flight's J, and the optimum no dearer.
    EXPECT_GT(gap.costs[i], 0.0);
    EXPECT_LT(gap.costs[i], run.summary.cost);
    EXPECT_LE(optimum->run.summary.cost, gap.costs[i]) << run.spec.label;
    EXPECT_GE(gap.gap_percent(i), 0.0);
  }
}

// With the input free at every controller sample, the transcription's objective at a flight's
// states and commands is the flight's J (the integral entries priced by the left-rectangle rule).
TEST(OptimalityGap, PricesAHelicopterFlightAsTheSimulatorDoes) {
  const Flight flight("hover-to-hover", short_ideal(0.2));
  PreparedController lqr = flight.prepare(parse_controller_spec("lqr"));
  const RunResult run = flight.fly(lqr);
  ASSERT_TRUE(run.completed());
  OptimalControlProblem problem;
  problem.plant = &flight.model();
  problem.reference = &flight.scenario().trajectory;
  problem.initial_state = flight.initial_state();
  problem.state_weights = flight.model().design_defaults().state_weights;
  problem.input_weights = flight.model().design_defaults().input_weights;
  problem.intervals = 200;
  problem.sampled_position_integral = heli::kXi;
  Eigen::MatrixXd states(200, heli::kStateDim), inputs(200, heli::kInputDim);
  for (Eigen::Index k = 0; k < 200; ++k) {
    states.row(k) = run.log.row(k).segment(4, heli::kStateDim).transpose();
    inputs.row(k) = run.log.row(k).segment(4 + 2 * heli::kStateDim, heli::kInputDim).transpose();
  }
  const ShootingTrajectory nodes = shooting_guess(problem, states, inputs);
  ShootingInterval interval(problem);
  Eigen::VectorXd next(problem.node_dim());
  double cost = 0.0;
  for (int k = 0; k < problem.intervals; ++k)
    cost += interval.propagate(k, nodes.nodes.row(k).transpose(), nodes.inputs.row(k).transpose(), next);
  EXPECT_NEAR(cost, run.summary.cost, 1e-12 * run.summary.cost);
}

TEST(OptimalityGap, RefusesWhatItCannotCompareBeforeFlying) {
  OptimalityOptions options;
  RunControls disturbed = short_ideal(1.0);
  disturbed.ideal = false;
  const Flight noisy("hover-to-hover", disturbed);
  std::vector<PreparedController> none;
  EXPECT_THAT(testing::error_message([&] { optimality_gap(noisy, none, options); }),
              HasSubstr("the flight has disturbances"));
  const Flight flight("hover-to-hover", short_ideal(1.0));
  options.control_interval = 0.0305;
  EXPECT_THAT(testing::error_message([&] { optimality_gap(flight, none, options); }),
              HasSubstr("control interval (0.030500 s) is not a whole number of controller periods"));
  options.control_interval = 0.3;
  EXPECT_THAT(testing::error_message([&] { optimality_gap(flight, none, options); }),
              HasSubstr("is not a whole number of control intervals"));
  options.control_interval = 0.05;
  options.start = 1.0;
  EXPECT_THAT(testing::error_message([&] { optimality_gap(flight, none, options); }),
              HasSubstr("the start (1.000000 s) leaves nothing of the 1.000000 s flight"));
  options.start = 0.5;
  options.warm_start = "lqr";
  EXPECT_THAT(testing::error_message([&] { optimality_gap(flight, none, options); }),
              HasSubstr("a warm start applies to a segment from t = 0"));
  options.start = 0.0;
  options.warm_start = "nobody";
  EXPECT_THAT(testing::error_message([&] { optimality_gap(flight, none, options); }),
              HasSubstr("the warm start nobody is none of the controllers flown"));
}

}  // namespace
}  // namespace thetad
