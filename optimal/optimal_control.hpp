#pragma once

#include <functional>
#include <string>

#include <Eigen/Core>

#include "core/ipopt_solve.hpp"
#include "optimal/optimal_control_problem.hpp"

namespace thetad {

// The unknowns of the multiple-shooting transcription: a node at the start of every shooting
// interval and at the horizon, and the input held over each interval.
struct ShootingTrajectory {
  Eigen::MatrixXd nodes;   // (intervals + 1) x node_dim
  Eigen::MatrixXd inputs;  // intervals x m
};

// The warm start from a flight: `states` (at least samples() rows of n) and `inputs` (at least
// samples() rows of m) at every controller sample from the problem's start. Nodes are the flight's states at
// the interval starts (with the integral it accumulated) and the last node what the last
// interval reaches; each interval holds the mean of the flight's inputs over it. Throws
// thetad::Error when the flight is too short or mis-sized.
ShootingTrajectory shooting_guess(const OptimalControlProblem& problem, const Eigen::MatrixXd& states,
                                  const Eigen::MatrixXd& inputs);

struct OptimalControlSettings {
  // tol 1e-6 on the scaled problem: J agrees to ~1e-9 relative with tighter solves.
  IpoptRun ipopt{.max_iterations = 1000,
                 .tolerance = 1e-6,
                 .constraint_tolerance = 1e-8,
                 .max_seconds = 1800,
                 .lbfgs_history = 30,
                 .user_scaling = true};
  // Called after every Ipopt iteration with its number, the objective and the largest defect.
  std::function<void(int iteration, double objective, double infeasibility)> progress;
};

struct OptimalControlSolution {
  IpoptOutcome outcome;
  int iterations = 0;
  double cost = 0.0;                  // J (or J_dev) of the solution: the sum of the intervals' costs from its nodes
  double constraint_violation = 0.0;  // largest |node − what the previous interval reaches|
  ShootingTrajectory shooting;
  // Every controller sample of the horizon, each interval propagated from its node: t, x (n), u (m),
  // and the tracking vector v (n) as J priced it.
  Eigen::MatrixXd samples;
};

// Solves `problem` by multiple shooting with Ipopt from `start`: equality constraints node_{k+1} =
// interval map(node_k, u_k), the first node fixed at the initial state, the inputs within the
// problem's bounds if it has any; exact first
// derivatives by ShootingInterval::linearize (sparse: one dense block per interval), Hessian by
// L-BFGS. Throws thetad::Error for an invalid problem or start, when the plant gives no Jacobian
// (SdcPlant::jacobian) or has no value at the start; a solve that does not converge is returned
// with its status (outcome.converged false).
OptimalControlSolution solve_optimal_control(const OptimalControlProblem& problem, const ShootingTrajectory& start,
                                             const OptimalControlSettings& settings = {});

}  // namespace thetad
