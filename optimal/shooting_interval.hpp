#pragma once

#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/control_law.hpp"
#include "core/sim/deviation_cost.hpp"
#include "core/sim/rk4.hpp"
#include "optimal/optimal_control_problem.hpp"

namespace thetad {

// The reference at each controller sample of the problem's horizon as the simulator gives it to
// the controller and the cost: its integral by the PositionIntegral rule from t = 0.
std::vector<Reference> sampled_references(const OptimalControlProblem& problem);

// The map of one shooting interval of an OptimalControlProblem and its derivatives: from a node
// (the plant state, then the sampled position-error integral when priced) with the input held,
// the interval's RK4 steps to the next node, and the cost (J or J_dev) of its controller samples.
class ShootingInterval {
 public:
  explicit ShootingInterval(const OptimalControlProblem& problem);

  // Called at every controller sample of propagate() with its time, node, tracking vector (its
  // integral entries as priced; for J_dev before V* is subtracted), and input.
  using SampleVisitor = std::function<void(double t, const Eigen::VectorXd& node, const Eigen::VectorXd& v,
                                           const Eigen::VectorXd& u)>;

  // The node after interval `interval` from `node` with `u` held (written to `next`), and the
  // interval's share of J. Throws thetad::Error when the plant has no value on the way.
  double propagate(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u, Eigen::VectorXd& next,
                   const SampleVisitor& visit = {});

  // propagate() and its derivative d(next node, cost)/d(node, u): (node_dim + 1) x (node_dim + m),
  // the cost in the last row. Exact to rounding: the RK4 steps' own sensitivities (each stage's
  // variational equation with the plant's exact Jacobian, SdcPlant::jacobian), not differences.
  // Throws thetad::Error when the plant has no value on the way or gives no Jacobian.
  double linearize(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u, Eigen::VectorXd& next,
                   Eigen::MatrixXd& derivative);

  // The node at the start of the horizon: the initial state and integral.
  Eigen::VectorXd initial_node() const;

 private:
  // propagate(), and with `sensitivities` the derivatives linearize() assembles.
  double run(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u, Eigen::VectorXd& next,
             const SampleVisitor& visit, bool sensitivities);
  // The stage of an RK4 step that starts from x_ (the stages rk4_step evaluates f at).
  const Eigen::VectorXd& stage(int i);
  // Advances sensitivity_ (d x / d(x at the node, u)) over the RK4 step from x_ whose stage slopes
  // are in workspace_.
  void step_sensitivity(const Eigen::VectorXd& u);
  // dfdx_ and dfdu_ at (x, u) by central differences of f, for a plant that gives no Jacobian.
  void differentiate(const Eigen::VectorXd& x, const Eigen::VectorXd& u);
  // J_dev's V* and u_r at x_ (into aim_state_, aim_input_) and, with `gradient`, their derivatives
  // in x by central differences (V* depends on x through the attitude only, smoothly).
  void aim(const Reference& reference, bool gradient);

  const OptimalControlProblem& problem_;
  int n_, m_, node_dim_;
  std::vector<Reference> references_;  // per controller sample of the horizon
  Eigen::MatrixXd tracking_gain_;      // d v / d x as priced: the tracking vector is affine in the state
  sim::Rk4Workspace workspace_;
  Eigen::VectorXd x_, v_, stage_, next_state_;
  // Sensitivities, columns (x at the node, u): of the state, of the sampled integral, of the stage
  // states and slopes; the plant's Jacobian at a stage; the cost's gradient (the node's integral
  // columns apart).
  Eigen::MatrixXd sensitivity_, integral_sensitivity_, stage_sensitivity_, slopes_[4], dfdx_, dfdu_;
  Eigen::RowVectorXd cost_gradient_;
  Eigen::RowVector3d cost_per_integral_;
  // J_dev: the commanded motion, the priced deviations, and V*'s and u_r's derivatives in x.
  std::optional<sim::DeviationCost> deviation_;
  Eigen::VectorXd error_, input_error_, aim_state_, aim_input_, probe_, state_plus_, input_plus_;
  Eigen::MatrixXd aim_state_gain_, aim_input_gain_;
};

}  // namespace thetad
