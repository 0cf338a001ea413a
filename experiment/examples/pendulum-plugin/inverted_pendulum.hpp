#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "core/sdc_plant.hpp"

namespace thetad::examples {

// The inverted pendulum: a point mass m on a massless rod of length l, pivoted at its foot, a
// torque u at the pivot, viscous friction b there, g = 9.81 m/s². With x = [θ, θ'] (θ from the
// upright, rad) and m = 1 kg:
//
//     θ'' = (g / l) sin θ − b θ' / l² + u / l²
//
// SDC factorization (F(x) x + B(x) u = f(x, u) exactly, sin θ = sinc(θ) θ):
//     F = [0 1; (g / l) sinc θ, −b / l²],   B = [0; 1 / l²].
// B never vanishes on θ', so (F(x), B) is controllable at every state; the plant is upright
// unstable for |θ| < π and the origin is its design point (u0 = 0).
class InvertedPendulum final : public SdcPlant {
 public:
  static constexpr double kGravity = 9.81;  // m/s²

  InvertedPendulum(double length, double damping) : length_(length), damping_(damping) {}

  int state_dim() const override { return 2; }
  int input_dim() const override { return 1; }

  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override {
    xdot[0] = x[1];
    xdot[1] = kGravity / length_ * std::sin(x[0]) + (-damping_ * x[1] + u[0]) / (length_ * length_);
  }

  void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>&,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override {
    // sinc θ by its series near 0, where sin θ / θ loses digits (the error is below 1e-17 there).
    const double t = x[0], sinc = std::abs(t) < 1e-4 ? 1.0 - t * t / 6.0 : std::sin(t) / t;
    F << 0.0, 1.0, kGravity / length_ * sinc, -damping_ / (length_ * length_);
    B << 0.0, 1.0 / (length_ * length_);
  }

  // df/dx and df/du by hand: `thetad optimal` needs them (without, it falls back on differences).
  bool jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>&,
                Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const override {
    dfdx << 0.0, 1.0, kGravity / length_ * std::cos(x[0]), -damping_ / (length_ * length_);
    dfdu << 0.0, 1.0 / (length_ * length_);
    return true;
  }

  std::vector<LogColumn> state_columns() const override { return {{"theta", "rad"}, {"theta_dot", "rad_per_s"}}; }
  std::vector<LogColumn> input_columns() const override { return {{"torque", "N_m"}}; }

 private:
  double length_;   // m
  double damping_;  // N m s/rad
};

}  // namespace thetad::examples
