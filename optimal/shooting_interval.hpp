#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "core/control_law.hpp"
#include "core/sim/rk4.hpp"
#include "optimal/optimal_control_problem.hpp"

namespace thetad {

// The map of one shooting interval of an OptimalControlProblem and its derivatives: from a node
// (the plant state, then the sampled position-error integral when priced) with the input held,
// the interval's RK4 steps to the next node, and the cost of its controller samples.
class ShootingInterval {
 public:
  explicit ShootingInterval(const OptimalControlProblem& problem);

  // Called at every controller sample of propagate() with its time, node, tracking vector as
  // priced, and input.
  using SampleVisitor = std::function<void(double t, const Eigen::VectorXd& node, const Eigen::VectorXd& v,
                                           const Eigen::VectorXd& u)>;

  // The node after interval `interval` from `node` with `u` held (written to `next`), and the
  // interval's share of J. Throws thetad::Error when the plant has no value on the way.
  double propagate(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u, Eigen::VectorXd& next,
                   const SampleVisitor& visit = {});

  // d(next node, cost)/d(node, u): (node_dim + 1) x (node_dim + m), the cost in the last row, by
  // central differences with steps eps^(1/3) max(1, |z_j|) (about 1e-10 relative where the plant
  // is smooth; exact to rounding where the map is at most quadratic, as on a linear plant).
  // Throws thetad::Error when the plant has no value at a perturbed point.
  void jacobian(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u, Eigen::MatrixXd& derivative);

  // The node at the start of the horizon: the initial state, the integral 0.
  Eigen::VectorXd initial_node() const;

 private:
  const OptimalControlProblem& problem_;
  int n_, m_, node_dim_;
  std::vector<Reference> references_;  // per controller sample
  sim::Rk4Workspace workspace_;
  Eigen::VectorXd x_, v_, node_plus_, node_minus_, u_plus_, u_minus_, next_plus_, next_minus_;
};

}  // namespace thetad
