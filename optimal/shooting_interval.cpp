#include "optimal/shooting_interval.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thetad {

ShootingInterval::ShootingInterval(const OptimalControlProblem& problem)
    : problem_(problem),
      n_(problem.plant->state_dim()),
      m_(problem.plant->input_dim()),
      node_dim_(problem.node_dim()),
      workspace_(n_),
      x_(n_),
      v_(n_),
      node_plus_(node_dim_),
      node_minus_(node_dim_),
      u_plus_(m_),
      u_minus_(m_),
      next_plus_(node_dim_),
      next_minus_(node_dim_) {
  // The reference as the simulators give it to the controller and the cost: its integral by the
  // PositionIntegral rule.
  const double period = problem.controller_period();
  PositionIntegral integral;
  references_.reserve(static_cast<std::size_t>(problem.samples()));
  for (int k = 0; k < problem.samples(); ++k) {
    const Eigen::Vector3d position = problem.reference->position(k * period);
    references_.push_back({position, integral.value});
    integral.accumulate(position, period);
  }
}

Eigen::VectorXd ShootingInterval::initial_node() const {
  Eigen::VectorXd node = Eigen::VectorXd::Zero(node_dim_);
  node.head(n_) = problem_.initial_state;
  return node;
}

double ShootingInterval::propagate(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u,
                                   Eigen::VectorXd& next, const SampleVisitor& visit) {
  const double period = problem_.controller_period();
  const auto& priced = problem_.sampled_position_integral;
  next = node;
  double cost = 0.0;
  for (int j = 0; j < problem_.interval_periods; ++j) {
    const int k = interval * problem_.interval_periods + j;
    const Reference& reference = references_[static_cast<std::size_t>(k)];
    x_ = next.head(n_);
    problem_.plant->tracking_vector(x_, reference, v_);
    if (priced) v_.segment<3>(*priced) = next.tail<3>();
    if (visit) visit(k * period, next, v_, u);
    // The same expression as the run metrics', so that a flight priced here costs what it cost.
    cost += 0.5 * (v_.cwiseAbs2().dot(problem_.state_weights) + u.cwiseAbs2().dot(problem_.input_weights)) * period;
    if (priced) next.tail<3>() += (x_.head<3>() - reference.position) * period;
    for (int step = 0; step < problem_.controller_period_steps; ++step)
      sim::rk4_step(*problem_.plant, u, problem_.dt, workspace_, x_);
    next.head(n_) = x_;
  }
  return cost;
}

void ShootingInterval::jacobian(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u,
                                Eigen::MatrixXd& derivative) {
  const double step_scale = std::cbrt(std::numeric_limits<double>::epsilon());
  derivative.resize(node_dim_ + 1, node_dim_ + m_);
  for (int j = 0; j < node_dim_ + m_; ++j) {
    node_plus_ = node_minus_ = node;
    u_plus_ = u_minus_ = u;
    const bool on_node = j < node_dim_;
    const double value = on_node ? node[j] : u[j - node_dim_];
    const double h = step_scale * std::max(1.0, std::abs(value));
    // The step actually taken, as represented: (z + h) − z is not h in floating point.
    double span;
    if (on_node) {
      node_plus_[j] = value + h;
      node_minus_[j] = value - h;
      span = node_plus_[j] - node_minus_[j];
    } else {
      u_plus_[j - node_dim_] = value + h;
      u_minus_[j - node_dim_] = value - h;
      span = u_plus_[j - node_dim_] - u_minus_[j - node_dim_];
    }
    const double cost_plus = propagate(interval, node_plus_, u_plus_, next_plus_);
    const double cost_minus = propagate(interval, node_minus_, u_minus_, next_minus_);
    derivative.col(j).head(node_dim_) = (next_plus_ - next_minus_) / span;
    derivative(node_dim_, j) = (cost_plus - cost_minus) / span;
  }
}

}  // namespace thetad
