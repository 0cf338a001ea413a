#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/sdc_plant.hpp"

namespace thetad {

// The rotational/translational actuator (RTAC, or TORA) of Bupp, Bernstein & Coppola, "A benchmark
// problem for nonlinear control design", Int. J. Robust Nonlinear Control 8 (1998): a cart on a
// linear spring, driven only through the torque on an eccentric mass that rotates on it. In the
// benchmark's dimensionless form, with x = [ξ, ξ', θ, θ'] (cart position and speed, rotor angle
// and rate), input u (the torque) and the coupling ε (0.2 in the benchmark), D = 1 − ε² cos²θ:
//
//     ξ'' = (−ξ + ε θ'² sin θ − ε cos θ u) / D
//     θ'' = (ε cos θ (ξ − ε θ'² sin θ) + u) / D
//
// SDC factorization (F(x) x + B(x) u = f(x, u) exactly):
//     F = [0 1 0 0; −1/D 0 0 ε θ' sin θ / D; 0 0 0 1; ε cos θ / D 0 0 −ε² cos θ sin θ θ' / D]
//     B = [0; −ε cos θ / D; 0; 1/D].
// It loses stabilizability where cos θ = 0 and θ' = 0: the cart's oscillation (modes ±i) then
// reaches neither the input nor the rotor.
class ToraPlant final : public SdcPlant {
 public:
  // Throws thetad::Error unless 0 < ε < 1 (D > 0).
  explicit ToraPlant(double epsilon = 0.2);

  int state_dim() const override { return 4; }
  int input_dim() const override { return 1; }
  double epsilon() const { return epsilon_; }

  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override;
  void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;
  // df/dx and df/du, by hand.
  bool jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const override;
  // xi, xi_dot, theta (rad), theta_dot (rad_per_s); the torque: all dimensionless but the angles.
  std::vector<LogColumn> state_columns() const override;
  std::vector<LogColumn> input_columns() const override;

 private:
  double epsilon_;
};

}  // namespace thetad
