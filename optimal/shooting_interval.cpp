#include "optimal/shooting_interval.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/central_differences.hpp"
#include "core/error.hpp"

namespace thetad {

std::vector<Reference> sampled_references(const OptimalControlProblem& problem) {
  const double period = problem.controller_period();
  PositionIntegral integral;
  std::vector<Reference> references;
  references.reserve(static_cast<std::size_t>(problem.samples()));
  for (int k = 0; k < problem.first_sample + problem.samples(); ++k) {
    const double t = k * period;
    const Eigen::Vector3d position = problem.reference->position(t);
    if (k >= problem.first_sample)
      references.push_back({position, integral.value, problem.reference->velocity(t), problem.reference->acceleration(t)});
    integral.accumulate(position, period);
  }
  return references;
}

ShootingInterval::ShootingInterval(const OptimalControlProblem& problem)
    : problem_(problem),
      n_(problem.plant->state_dim()),
      m_(problem.plant->input_dim()),
      node_dim_(problem.node_dim()),
      references_(sampled_references(problem)),
      tracking_gain_(n_, n_),
      workspace_(n_),
      x_(n_),
      v_(n_),
      stage_(n_),
      next_state_(n_),
      sensitivity_(n_, n_ + m_),
      integral_sensitivity_(3, n_ + m_),
      stage_sensitivity_(n_, n_ + m_),
      dfdx_(n_, n_),
      dfdu_(n_, m_),
      cost_gradient_(n_ + m_),
      error_(n_),
      input_error_(m_),
      aim_state_(n_),
      aim_input_(m_),
      probe_(n_),
      state_plus_(n_),
      input_plus_(m_),
      aim_state_gain_(n_, n_),
      aim_input_gain_(m_, n_) {
  for (auto& slope : slopes_) slope.resize(n_, n_ + m_);
  if (problem.deviation_trims) {
    deviation_.emplace(*problem.plant, problem.deviation_trims,
                       sim::DeviationWeights{problem.state_weights, problem.input_weights, "the problem's"},
                       problem.controller_period());
  }
  // The tracking vector is the state less the reference (affine in the state), so its columns at
  // a zero reference are exact: v(e_j) - v(0). The rows priced by the sampled integral instead are 0.
  const Reference zero;
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(n_), at_zero(n_);
  problem.plant->tracking_vector(unit, zero, at_zero);
  for (int j = 0; j < n_; ++j) {
    unit[j] = 1.0;
    problem.plant->tracking_vector(unit, zero, v_);
    tracking_gain_.col(j) = v_ - at_zero;
    unit[j] = 0.0;
  }
  if (problem.sampled_position_integral) tracking_gain_.middleRows<3>(*problem.sampled_position_integral).setZero();
}

Eigen::VectorXd ShootingInterval::initial_node() const {
  Eigen::VectorXd node = Eigen::VectorXd::Zero(node_dim_);
  node.head(n_) = problem_.initial_state;
  if (problem_.sampled_position_integral) node.tail<3>() = problem_.initial_integral;
  return node;
}

double ShootingInterval::propagate(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u,
                                   Eigen::VectorXd& next, const SampleVisitor& visit) {
  return run(interval, node, u, next, visit, false);
}

double ShootingInterval::linearize(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u,
                                   Eigen::VectorXd& next, Eigen::MatrixXd& derivative) {
  const double cost = run(interval, node, u, next, {}, true);
  derivative.resize(node_dim_ + 1, node_dim_ + m_);
  derivative.setZero();
  derivative.topLeftCorner(n_, n_) = sensitivity_.leftCols(n_);
  derivative.block(0, node_dim_, n_, m_) = sensitivity_.rightCols(m_);
  derivative.row(node_dim_).head(n_) = cost_gradient_.head(n_);
  derivative.row(node_dim_).tail(m_) = cost_gradient_.tail(m_);
  if (problem_.sampled_position_integral) {
    derivative.block(n_, 0, 3, n_) = integral_sensitivity_.leftCols(n_);
    derivative.block<3, 3>(n_, n_).setIdentity();  // the integral carries on from the node's
    derivative.block(n_, node_dim_, 3, m_) = integral_sensitivity_.rightCols(m_);
    derivative.row(node_dim_).segment<3>(n_) = cost_per_integral_;
  }
  return cost;
}

double ShootingInterval::run(int interval, const Eigen::VectorXd& node, const Eigen::VectorXd& u, Eigen::VectorXd& next,
                             const SampleVisitor& visit, bool sensitivities) {
  const double period = problem_.controller_period();
  const auto& priced = problem_.sampled_position_integral;
  next = node;
  double cost = 0.0;
  if (sensitivities) {
    sensitivity_.setZero();
    sensitivity_.leftCols(n_).setIdentity();
    integral_sensitivity_.setZero();
    cost_gradient_.setZero();
    cost_per_integral_.setZero();
  }
  for (int j = 0; j < problem_.interval_periods; ++j) {
    const int k = interval * problem_.interval_periods + j;
    const Reference& reference = references_[static_cast<std::size_t>(k)];
    x_ = next.head(n_);
    problem_.plant->tracking_vector(x_, reference, v_);
    if (priced) v_.segment<3>(*priced) = next.tail<3>();
    if (visit) visit((problem_.first_sample + k) * period, next, v_, u);
    error_ = v_;
    input_error_ = u;
    if (deviation_) {
      aim(reference, sensitivities);
      error_ -= aim_state_;
      input_error_ -= aim_input_;
    }
    // The same expression as the run metrics', so that a flight priced here costs what it cost.
    cost += 0.5 * (error_.cwiseAbs2().dot(problem_.state_weights) +
                   input_error_.cwiseAbs2().dot(problem_.input_weights)) *
            period;
    if (sensitivities) {
      const Eigen::RowVectorXd weighted = period * error_.cwiseProduct(problem_.state_weights).transpose();
      const Eigen::RowVectorXd input_weighted = period * input_error_.cwiseProduct(problem_.input_weights).transpose();
      if (deviation_) {
        cost_gradient_.noalias() +=
            (weighted * (tracking_gain_ - aim_state_gain_) - input_weighted * aim_input_gain_) * sensitivity_;
      } else {
        cost_gradient_.noalias() += (weighted * tracking_gain_) * sensitivity_;
      }
      cost_gradient_.tail(m_) += input_weighted;
      if (priced) {
        cost_gradient_.noalias() += weighted.segment<3>(*priced) * integral_sensitivity_;
        cost_per_integral_ += weighted.segment<3>(*priced);
        integral_sensitivity_ += period * sensitivity_.topRows<3>();
      }
    }
    if (priced) next.tail<3>() += (x_.head<3>() - reference.position) * period;
    for (int step = 0; step < problem_.controller_period_steps; ++step) {
      if (!sensitivities) {
        sim::rk4_step(*problem_.plant, u, problem_.dt, workspace_, x_);
        continue;
      }
      next_state_ = x_;
      sim::rk4_step(*problem_.plant, u, problem_.dt, workspace_, next_state_);
      step_sensitivity(u);
      x_ = next_state_;
    }
    next.head(n_) = x_;
  }
  return cost;
}

void ShootingInterval::aim(const Reference& reference, bool gradient) {
  deviation_->target(x_, reference, aim_state_, aim_input_);
  if (!gradient) return;
  // Central differences with the step that balances their truncation and rounding errors.
  const double step = std::cbrt(std::numeric_limits<double>::epsilon());
  probe_ = x_;
  for (int j = 0; j < n_; ++j) {
    const double h = step * std::max(1.0, std::abs(x_[j]));
    probe_[j] = x_[j] + h;
    deviation_->target(probe_, reference, state_plus_, input_plus_);
    aim_state_gain_.col(j) = state_plus_;
    aim_input_gain_.col(j) = input_plus_;
    probe_[j] = x_[j] - h;
    deviation_->target(probe_, reference, state_plus_, input_plus_);
    aim_state_gain_.col(j) = (aim_state_gain_.col(j) - state_plus_) / (2.0 * h);
    aim_input_gain_.col(j) = (aim_input_gain_.col(j) - input_plus_) / (2.0 * h);
    probe_[j] = x_[j];
  }
}

const Eigen::VectorXd& ShootingInterval::stage(int i) {
  const double dt = problem_.dt;
  switch (i) {  // as rk4_step forms them, so that the Jacobians are taken where f was
    case 0: stage_ = x_; break;
    case 1: stage_ = x_ + (0.5 * dt) * workspace_.k1; break;
    case 2: stage_ = x_ + (0.5 * dt) * workspace_.k2; break;
    default: stage_ = x_ + dt * workspace_.k3;
  }
  return stage_;
}

void ShootingInterval::differentiate(const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
  Eigen::VectorXd z(n_ + m_);
  z << x, u;
  const Eigen::MatrixXd dfdz =
      central_differences([this](const Eigen::VectorXd& at) { return problem_.plant->f(at.head(n_), at.tail(m_)); }, z);
  dfdx_ = dfdz.leftCols(n_);
  dfdu_ = dfdz.rightCols(m_);
}

// RK4's stage slopes k_i = f(x + c_i dt k_{i-1}, u) differentiate to K_i = A_i (S + c_i dt K_{i-1})
// + [0 B_i], with A_i, B_i the plant's Jacobian at stage i; the step S+ = S + dt/6 (K1 + 2 K2 +
// 2 K3 + K4) is the exact derivative of the step x+ that rk4_step takes.
void ShootingInterval::step_sensitivity(const Eigen::VectorXd& u) {
  const double dt = problem_.dt;
  const double offset[4] = {0.0, 0.5 * dt, 0.5 * dt, dt};
  for (int i = 0; i < 4; ++i) {
    if (!problem_.plant->jacobian(stage(i), u, dfdx_, dfdu_)) {
      if (!problem_.finite_differences)
        throw Error("optimal control: the plant gives no Jacobian of f (SdcPlant::jacobian), which the transcription "
                    "needs (or allow central differences: OptimalControlProblem::finite_differences)");
      differentiate(stage(i), u);
    }
    if (i == 0) {
      slopes_[0].noalias() = dfdx_ * sensitivity_;
    } else {
      stage_sensitivity_ = sensitivity_ + offset[i] * slopes_[i - 1];
      slopes_[i].noalias() = dfdx_ * stage_sensitivity_;
    }
    slopes_[i].rightCols(m_) += dfdu_;
  }
  sensitivity_ += (dt / 6.0) * (slopes_[0] + 2.0 * slopes_[1] + 2.0 * slopes_[2] + slopes_[3]);
}

}  // namespace thetad
