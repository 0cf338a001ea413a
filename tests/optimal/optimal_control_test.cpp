// The multiple-shooting transcription against what is known exactly on a linear plant: the
// discrete-time finite-horizon LQR on the same RK4 discretisation, computed here on its own.
#include "optimal/optimal_control.hpp"

#include <Eigen/Cholesky>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "core/sim/simulator.hpp"
#include "optimal/shooting_interval.hpp"
#include "tests/optimal/interval_differences.hpp"
#include "tests/error_message.hpp"
#include "tests/test_plants.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;

const FixedPosition kOrigin(Eigen::Vector3d::Zero());

// An unstable, lightly coupled 3-state, 2-input plant.
LinearPlant small_plant() {
  Eigen::MatrixXd A(3, 3), B(3, 2);
  A << 0.2, 1.0, 0.0,  //
      -1.0, -0.3, 0.5,  //
      0.1, 0.0, -0.8;
  B << 0.0, 0.3,  //
      1.0, 0.0,   //
      0.2, 1.0;
  return {A, B};
}

OptimalControlProblem problem_for(const LinearPlant& plant) {
  OptimalControlProblem problem;
  problem.plant = &plant;
  problem.reference = &kOrigin;
  problem.initial_state = Eigen::Vector3d(1.0, -0.5, 0.8);
  problem.state_weights = Eigen::Vector3d(2.0, 1.0, 0.5);
  problem.input_weights = Eigen::Vector2d(0.3, 1.5);
  problem.dt = 0.01;
  problem.controller_period_steps = 2;  // T_c = 20 ms
  problem.interval_periods = 3;         // u held 60 ms
  problem.intervals = 25;               // 1.5 s
  return problem;
}

// One RK4 step of xdot = A x + B u with u held is x+ = Φ x + Γ u, Φ and Γ the degree-4 Taylor
// polynomials (classical RK4 is exact to that order on a linear system).
struct Discrete {
  Eigen::MatrixXd Phi, Gamma;
};

Discrete rk4_step(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double h) {
  const Eigen::Index n = A.rows();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n), A2 = A * A, A3 = A2 * A;
  return {I + h * A + h * h / 2 * A2 + h * h * h / 6 * A3 + h * h * h * h / 24 * A3 * A,
          (h * I + h * h / 2 * A + h * h * h / 6 * A2 + h * h * h * h / 24 * A3) * B};
}

// x after `steps` steps of `one` from x with u held: [Φ^steps, Γ_steps].
Discrete repeat(const Discrete& one, int steps) {
  Discrete many{Eigen::MatrixXd::Identity(one.Phi.rows(), one.Phi.cols()), Eigen::MatrixXd::Zero(one.Gamma.rows(), one.Gamma.cols())};
  for (int i = 0; i < steps; ++i) many = {one.Phi * many.Phi, one.Phi * many.Gamma + one.Gamma};
  return many;
}

// The finite-horizon LQR over the shooting intervals: an interval's cost is the quadratic
// ½ [x; u]ᵀ M [x; u] of its samples' ½ (xᵀQx + uᵀRu) T_c, and it moves x by [Φ^K, Γ_K]; the
// backward Riccati recursion with cross terms from P_N = 0 gives the optimum ½ x0ᵀ P_0 x0.
double lqr_cost(const LinearPlant& plant, const OptimalControlProblem& p) {
  const Eigen::Index n = plant.state_dim(), m = plant.input_dim();
  const Discrete sample = repeat(rk4_step(plant.A(), plant.B(), p.dt), p.controller_period_steps);
  const double period = p.controller_period();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + m, n + m), map(n, n + m);
  Eigen::MatrixXd QR = Eigen::MatrixXd::Zero(n + m, n + m);
  QR.diagonal() << p.state_weights, p.input_weights;
  Discrete reached{Eigen::MatrixXd::Identity(n, n), Eigen::MatrixXd::Zero(n, m)};
  for (int j = 0; j < p.interval_periods; ++j) {
    Eigen::MatrixXd z = Eigen::MatrixXd::Zero(n + m, n + m);  // [x_j; u] in terms of [x; u]
    z.topLeftCorner(n, n) = reached.Phi;
    z.topRightCorner(n, m) = reached.Gamma;
    z.bottomRightCorner(m, m).setIdentity();
    M += period * z.transpose() * QR * z;
    reached = {sample.Phi * reached.Phi, sample.Phi * reached.Gamma + sample.Gamma};
  }
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(n, n);
  for (int k = p.intervals - 1; k >= 0; --k) {
    const Eigen::MatrixXd Huu = M.bottomRightCorner(m, m) + reached.Gamma.transpose() * P * reached.Gamma;
    const Eigen::MatrixXd Hux = M.bottomLeftCorner(m, n) + reached.Gamma.transpose() * P * reached.Phi;
    P = M.topLeftCorner(n, n) + reached.Phi.transpose() * P * reached.Phi - Hux.transpose() * Huu.ldlt().solve(Hux);
  }
  return 0.5 * p.initial_state.dot(P * p.initial_state);
}

// A do-nothing "flight" to start from: x0 held, u = 0.
ShootingTrajectory idle_start(const OptimalControlProblem& p) {
  const Eigen::MatrixXd states = p.initial_state.transpose().replicate(p.samples(), 1);
  return shooting_guess(p, states, Eigen::MatrixXd::Zero(p.samples(), p.plant->input_dim()));
}

TEST(OptimalControl, OnALinearPlantCostsWhatTheFiniteHorizonLqrSays) {
  const LinearPlant plant = small_plant();
  const OptimalControlProblem problem = problem_for(plant);
  const OptimalControlSolution solution = solve_optimal_control(problem, idle_start(problem));
  ASSERT_TRUE(solution.outcome.converged) << solution.outcome.status;
  const double expected = lqr_cost(plant, problem);
  EXPECT_NEAR(solution.cost, expected, 1e-6 * expected);
  EXPECT_LE(solution.constraint_violation, 1e-8);
  EXPECT_EQ(solution.samples.rows(), problem.samples());
  EXPECT_EQ(solution.samples.row(0).segment(1, 3), problem.initial_state.transpose());
}

// J of the inputs alone (one row per interval), the nodes rolled forward from the initial state.
double rolled_cost(const OptimalControlProblem& problem, const Eigen::MatrixXd& inputs) {
  ShootingInterval interval(problem);
  Eigen::VectorXd node = interval.initial_node(), next(node.size());
  double cost = 0.0;
  for (int k = 0; k < problem.intervals; ++k) {
    cost += interval.propagate(k, node, inputs.row(k).transpose(), next);
    node = next;
  }
  return cost;
}

// With input bounds that bind, the solution is a minimum of the box-constrained problem: its KKT
// conditions hold on the condensed cost (gradient zero off the bounds, pointing out of the box on
// them), and it costs more than the unbounded optimum.
TEST(OptimalControl, OnALinearPlantWithBoundsMeetsTheBoxConstrainedOptimality) {
  const LinearPlant plant = small_plant();
  OptimalControlProblem problem = problem_for(plant);
  OptimalControlSettings settings;
  settings.ipopt.tolerance = 1e-10;
  const OptimalControlSolution free = solve_optimal_control(problem, idle_start(problem), settings);
  ASSERT_TRUE(free.outcome.converged);
  const Eigen::VectorXd reach = free.shooting.inputs.cwiseAbs().colwise().maxCoeff().transpose();
  problem.input_lower = -0.4 * reach;
  problem.input_upper = 0.4 * reach;
  const OptimalControlSolution bounded = solve_optimal_control(problem, idle_start(problem), settings);
  ASSERT_TRUE(bounded.outcome.converged) << bounded.outcome.status;
  EXPECT_GT(bounded.cost, free.cost * 1.01);
  EXPECT_LE(bounded.constraint_violation, 1e-8);
  const Eigen::MatrixXd& u = bounded.shooting.inputs;
  // The condensed cost is quadratic in u: its central differences are exact but for rounding.
  const auto cost_of = [&](const Eigen::VectorXd& flat) {
    Eigen::VectorXd value(1);
    value[0] = rolled_cost(problem, Eigen::Map<const Eigen::MatrixXd>(flat.data(), u.rows(), u.cols()));
    return value;
  };
  const Eigen::VectorXd flat = Eigen::Map<const Eigen::VectorXd>(u.data(), u.size());
  const Eigen::VectorXd gradient = testing::central_differences(cost_of, flat).transpose();
  const Eigen::VectorXd scale =
      testing::central_differences(cost_of, Eigen::VectorXd::Zero(u.size())).transpose().cwiseAbs();
  const double tolerance = 1e-6 * scale.maxCoeff();
  int at_bounds = 0;
  for (Eigen::Index k = 0; k < u.rows(); ++k) {
    for (Eigen::Index i = 0; i < u.cols(); ++i) {
      const double g = gradient[i * u.rows() + k], margin = 1e-6 * reach[i];
      ASSERT_GE(u(k, i), problem.input_lower[i] - 1e-12);
      ASSERT_LE(u(k, i), problem.input_upper[i] + 1e-12);
      if (u(k, i) < problem.input_lower[i] + margin) {
        EXPECT_GE(g, -tolerance) << k << ", " << i;
        ++at_bounds;
      } else if (u(k, i) > problem.input_upper[i] - margin) {
        EXPECT_LE(g, tolerance) << k << ", " << i;
        ++at_bounds;
      } else {
        EXPECT_LE(std::abs(g), tolerance) << k << ", " << i;
      }
    }
  }
  EXPECT_GT(at_bounds, 0);
}

TEST(OptimalControl, IntervalDerivativesAreTheDiscreteMapOnALinearPlant) {
  const LinearPlant plant = small_plant();
  const OptimalControlProblem problem = problem_for(plant);
  ShootingInterval interval(problem);
  Eigen::VectorXd next(3);
  Eigen::MatrixXd derivative;
  interval.linearize(4, problem.initial_state, Eigen::Vector2d(0.7, -0.2), next, derivative);
  const Discrete exact =
      repeat(rk4_step(plant.A(), plant.B(), problem.dt), problem.controller_period_steps * problem.interval_periods);
  EXPECT_LE((derivative.topLeftCorner(3, 3) - exact.Phi).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LE((derivative.topRightCorner(3, 2) - exact.Gamma).cwiseAbs().maxCoeff(), 1e-14);
}

// The whole block, the cost row too, against central differences of the interval map at random
// nodes and inputs (the map is at most quadratic: the differences are exact but for rounding).
TEST(OptimalControl, IntervalDerivativesAreCentralDifferencesOnALinearPlant) {
  const LinearPlant plant = small_plant();
  const OptimalControlProblem problem = problem_for(plant);
  ShootingInterval interval(problem);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd z = Eigen::VectorXd::NullaryExpr(5, [&] { return normal(rng); });
    const int k = trial % problem.intervals;
    Eigen::VectorXd next(3), reached(3);
    Eigen::MatrixXd derivative;
    const double cost = interval.linearize(k, z.head(3), z.tail(2), next, derivative);
    EXPECT_EQ(cost, interval.propagate(k, z.head(3), z.tail(2), reached));
    EXPECT_EQ(next, reached);
    EXPECT_LT(testing::row_relative_error(derivative, testing::interval_differences(interval, k, z, 3)), 1e-9);
  }
}

// The objective is J as the plant simulator prices a flight, sample for sample.
TEST(OptimalControl, PricesAFlightAsTheSimulatorDoes) {
  const LinearPlant plant = small_plant();
  OptimalControlProblem problem = problem_for(plant);
  problem.interval_periods = 1;
  problem.intervals = 40;
  problem.state_weights = plant.design_defaults().state_weights;
  problem.input_weights = plant.design_defaults().input_weights;
  ConstantInput law(Eigen::Vector2d(0.4, -0.3));
  sim::SimulationSettings settings;
  settings.dt = problem.dt;
  settings.controller_period_steps = problem.controller_period_steps;
  settings.duration = problem.horizon();
  sim::NoDisturbances as_it_is(plant);
  const sim::RunResult run = sim::simulate(law, as_it_is, kOrigin, problem.initial_state, settings);
  ASSERT_EQ(run.summary.status, sim::RunStatus::completed);
  // Rows t, x (3), measured x (3), command (2), applied (2), compute time.
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> log(
      run.log.values.data(), run.log.rows(), static_cast<Eigen::Index>(run.log.columns.size()));
  const ShootingTrajectory nodes = shooting_guess(problem, log.middleCols(1, 3), log.middleCols(7, 2));
  ShootingInterval interval(problem);
  Eigen::VectorXd next(3);
  double cost = 0.0;
  for (int k = 0; k < problem.intervals; ++k)
    cost += interval.propagate(k, nodes.nodes.row(k).transpose(), nodes.inputs.row(k).transpose(), next);
  EXPECT_NEAR(cost, run.summary.cost, 1e-12 * run.summary.cost);
}

TEST(OptimalControl, BadProblemsAndStartsAreRefusedClearly) {
  const LinearPlant plant = small_plant();
  OptimalControlProblem problem = problem_for(plant);
  problem.state_weights = Eigen::Vector2d(1.0, 1.0);
  EXPECT_THAT(testing::error_message([&] { problem.validate(); }),
              HasSubstr("state_weights has 2 entries, the plant needs 3"));
  problem = problem_for(plant);
  problem.interval_periods = 0;
  EXPECT_THAT(testing::error_message([&] { problem.validate(); }), HasSubstr("interval_periods must be at least 1"));
  problem = problem_for(plant);
  problem.input_lower = Eigen::Vector2d(-1.0, 1.0);
  problem.input_upper = Eigen::Vector2d(1.0, 0.5);
  EXPECT_THAT(testing::error_message([&] { problem.validate(); }), HasSubstr("input_lower exceeds input_upper"));
  problem.input_upper.resize(0);
  EXPECT_THAT(testing::error_message([&] { problem.validate(); }),
              HasSubstr("input_upper has 0 entries, the plant needs 2"));
  problem = problem_for(plant);
  problem.sampled_position_integral = 1;
  EXPECT_THAT(testing::error_message([&] { problem.validate(); }), HasSubstr("sampled_position_integral 1"));
  problem = problem_for(plant);
  EXPECT_THAT(testing::error_message([&] {
                shooting_guess(problem, Eigen::MatrixXd::Zero(10, 3), Eigen::MatrixXd::Zero(10, 2));
              }),
              HasSubstr("the warm start has 10 samples of 3 states"));
  ShootingTrajectory start = idle_start(problem);
  start.inputs.conservativeResize(3, Eigen::NoChange);
  EXPECT_THAT(testing::error_message([&] { solve_optimal_control(problem, start); }),
              HasSubstr("the start's inputs is 3x2, expected 25x2"));
}

}  // namespace
}  // namespace thetad
