// The optimality gap on the helicopter, over a short horizon of the shipped hover-to-hover move:
// the optimum Ipopt finds costs no more than any built-in controller's flight, on J and on J_dev,
// bounded and unbounded, and the transcription prices a flight exactly as the simulator does.
#include "optimal/optimality_gap.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

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
  options.cost = OptimalCost::paper;
  options.control_interval = 0.05;
  const OptimalityGap gap = optimality_gap(flight, controllers, options);
  ASSERT_EQ(gap.optima.size(), 1u);
  EXPECT_FALSE(gap.optima[0].unbounded);  // no limits, one solve
  const OptimalControlSolution& solution = gap.optima[0].optimum.solution;
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
  const RunResult& optimum = gap.optima[0].optimum.run;
  EXPECT_NEAR(optimum.summary.cost, solution.cost, 1e-12 * solution.cost);
  EXPECT_EQ(optimum.log.rows(), 500);
  EXPECT_TRUE(optimum.completed());
}

// The comparison's score: the optimum of J_dev, by default, with the flights' J_dev as their
// summaries have it, and the optimum's run scored by the flights' own J_dev.
TEST(OptimalityGap, TheJDevOptimumCostsNoMoreThanAnyControllerOnTheHelicopter) {
  const Flight flight("hover-to-hover", short_ideal(0.5));
  std::vector<PreparedController> controllers = built_in(flight);
  const OptimalityGap gap = optimality_gap(flight, controllers, OptimalityOptions{});
  ASSERT_EQ(gap.cost, OptimalCost::deviation);
  ASSERT_EQ(gap.optima.size(), 1u);
  const SolvedOptimum& optimum = gap.optima[0].optimum;
  ASSERT_TRUE(optimum.solution.outcome.converged) << optimum.solution.outcome.status;
  ASSERT_TRUE(optimum.run.summary.cost_dev);
  EXPECT_NEAR(*optimum.run.summary.cost_dev, optimum.solution.cost, 1e-12 * optimum.solution.cost);
  EXPECT_EQ(gap.optima[0].cost(OptimalCost::deviation), *optimum.run.summary.cost_dev);
  for (std::size_t i = 0; i < gap.flights.size(); ++i) {
    const RunResult& run = gap.flights[i];
    ASSERT_TRUE(run.completed() && run.summary.cost_dev) << run.spec.label;
    EXPECT_EQ(gap.costs[i], *run.summary.cost_dev);
    EXPECT_LE(optimum.solution.cost, *run.summary.cost_dev) << run.spec.label;
    EXPECT_GE(gap.gap_percent(i), 0.0) << run.spec.label;
    EXPECT_TRUE(std::isnan(gap.unbounded_gap_percent(i)));
  }
}

// With actuator limits the flights fly them and the optimum is bounded by their magnitudes; the
// unbounded optimum, started from the bounded one, costs no more.
TEST(OptimalityGap, WithLimitsTheOptimumIsBoundedAndTheUnboundedOneNoDearer) {
  RunControls controls = short_ideal(0.5);
  controls.actuator_limits = true;
  const Flight flight("hover-step", controls);
  std::vector<PreparedController> controllers;
  for (const char* name : {"lqr", "lqr-scheduled"}) controllers.push_back(flight.prepare(parse_controller_spec(name)));
  OptimalityOptions options;
  options.cost = OptimalCost::paper;  // the paper's weights push the inputs to their bounds
  const OptimalityGap gap = optimality_gap(flight, controllers, options);
  ASSERT_EQ(gap.optima.size(), 1u);
  const SegmentOptimum& segment = gap.optima[0];
  ASSERT_TRUE(segment.problem.bounded());
  ASSERT_TRUE(segment.unbounded);
  EXPECT_EQ(segment.optimum.run.spec.label, "optimal");
  EXPECT_EQ(segment.unbounded->run.spec.label, "optimal-unbounded");
  ASSERT_TRUE(segment.optimum.solution.outcome.converged) << segment.optimum.solution.outcome.status;
  ASSERT_TRUE(segment.unbounded->solution.outcome.converged) << segment.unbounded->solution.outcome.status;
  const Eigen::MatrixXd& inputs = segment.optimum.solution.shooting.inputs;
  const sim::ActuatorLimits& limits = flight.settings().actuator_limits;
  for (Eigen::Index k = 0; k < inputs.rows(); ++k) {
    EXPECT_TRUE((inputs.row(k).transpose().array() >= limits.lower.array() - 1e-9).all()) << k;
    EXPECT_TRUE((inputs.row(k).transpose().array() <= limits.upper.array() + 1e-9).all()) << k;
  }
  const double bounded = segment.cost(OptimalCost::paper), unbounded = segment.unbounded_cost(OptimalCost::paper);
  EXPECT_LE(unbounded, bounded * (1.0 + 1e-6));
  for (std::size_t i = 0; i < gap.flights.size(); ++i) {
    ASSERT_TRUE(gap.flights[i].completed()) << gap.flights[i].spec.label;
    EXPECT_GE(gap.gap_percent(i), 0.0);
    EXPECT_GE(gap.unbounded_gap_percent(i), gap.gap_percent(i) - 1e-4);
  }
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
    const RunResult& best = optimum->optimum.run;
    EXPECT_EQ(best.spec.label, "optimal-from-" + run.spec.label);
    ASSERT_TRUE(optimum->optimum.solution.outcome.converged) << optimum->optimum.solution.outcome.status;
    EXPECT_EQ(optimum->problem.first_sample, 300);
    EXPECT_EQ(best.log.rows(), 300);
    EXPECT_DOUBLE_EQ(best.log.row(0)(0), 0.3);
    EXPECT_EQ(best.log.row(0).segment(4, heli::kStateDim), run.log.row(300).segment(4, heli::kStateDim));
    // The segment is the later part of the flight's J_dev, and the optimum no dearer.
    EXPECT_GT(gap.costs[i], 0.0);
    EXPECT_LT(gap.costs[i], *run.summary.cost_dev);
    EXPECT_LE(*best.summary.cost_dev, gap.costs[i]) << run.spec.label;
    EXPECT_GE(gap.gap_percent(i), 0.0);
  }
}

// The transcription's objective, with the input free at every controller sample, at a flight's
// states and commands: J or J_dev on the samples of `run`.
double priced(const Flight& flight, const RunResult& run, OptimalControlProblem problem) {
  problem.plant = &flight.model();
  problem.reference = &flight.scenario().trajectory;
  problem.initial_state = flight.initial_state();
  problem.intervals = static_cast<int>(run.log.rows());
  problem.sampled_position_integral = heli::kXi;
  Eigen::MatrixXd states(run.log.rows(), heli::kStateDim), inputs(run.log.rows(), heli::kInputDim);
  for (Eigen::Index k = 0; k < run.log.rows(); ++k) {
    states.row(k) = run.log.row(k).segment(4, heli::kStateDim).transpose();
    inputs.row(k) = run.log.row(k).segment(4 + 2 * heli::kStateDim, heli::kInputDim).transpose();
  }
  const ShootingTrajectory nodes = shooting_guess(problem, states, inputs);
  ShootingInterval interval(problem);
  Eigen::VectorXd next(problem.node_dim());
  double cost = 0.0;
  for (int k = 0; k < problem.intervals; ++k)
    cost += interval.propagate(k, nodes.nodes.row(k).transpose(), nodes.inputs.row(k).transpose(), next);
  return cost;
}

// The flight's J (the integral entries priced by the left-rectangle rule) and its J_dev, in a move
// (the commanded velocity resolved in the flown attitude) with the actuator limits acting.
TEST(OptimalityGap, PricesAHelicopterFlightAsTheSimulatorDoes) {
  RunControls controls = short_ideal(1.5);
  controls.actuator_limits = true;
  const Flight flight("hover-to-hover", controls);
  PreparedController theta_d = flight.prepare(parse_controller_spec("theta-d"));
  const RunResult run = flight.fly(theta_d);
  ASSERT_TRUE(run.completed() && run.summary.cost_dev);
  ASSERT_GT(run.summary.saturation.samples_limited, 0);  // the commands J prices are not all what flew
  OptimalControlProblem problem;
  problem.state_weights = flight.model().design_defaults().state_weights;
  problem.input_weights = flight.model().design_defaults().input_weights;
  EXPECT_NEAR(priced(flight, run, problem), run.summary.cost, 1e-12 * run.summary.cost);
  std::string why_not;
  const std::optional<sim::DeviationCost> deviation = flight.deviation_cost(why_not);
  ASSERT_TRUE(deviation) << why_not;
  problem.state_weights = deviation->weights().state;
  problem.input_weights = deviation->weights().input;
  problem.deviation_trims = deviation->trims();
  EXPECT_NEAR(priced(flight, run, problem), *run.summary.cost_dev, 1e-12 * *run.summary.cost_dev);
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
  // J_dev needs the trims of the commanded motion: none beyond 20 m/s.
  RunControls fast = short_ideal(1.0);
  fast.speed_scale = 100.0;
  const Flight beyond("hover-to-hover", fast);
  EXPECT_THAT(testing::error_message([&] { optimality_problem(beyond, OptimalityOptions{}); }),
              HasSubstr("this flight has no J_dev (none: "));
}

}  // namespace
}  // namespace thetad
