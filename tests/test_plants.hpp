#pragma once

// Small SDC plants for the controller tests and the scaling benchmark: one whose SDRE solution is
// known in closed form, a generic n-dimensional one, and a linear one. Neither knows anything about helicopters;
// both satisfy F(x; u) x + B(x; u) u == f(x, u) exactly (f is defined through F and B).

#include <cstdint>

#include <Eigen/Core>

#include "core/sdc_plant.hpp"

namespace thetad {

// A Duffing-type oscillator in companion form with a state-dependent input gain:
//
//     x1' = x2
//     x2' = a1(x) x1 + a2(x) x2 + b(x) u,     a1 = −1 + x1²,  a2 = −0.5 + 0.3 x1 x2,  b = 1 + 0.5 x1²
//
// i.e. x2' = −x1 + x1³ − 0.5 x2 + 0.3 x1 x2² + (1 + 0.5 x1²) u, with the SDC factorization
// F(x) = [0 1; a1 a2], B(x) = [0; b].
//
// SDRE in closed form. For Q = diag(q1, q2), R = r > 0 the equation
// PF + FᵀP − P B r⁻¹ Bᵀ P + Q = 0 with P = [p1 p2; p2 p3] reads, entry by entry,
//     (1,1)  2 a1 p2 − b² p2² / r + q1 = 0
//     (2,2)  2 p2 + 2 a2 p3 − b² p3² / r + q2 = 0
//     (1,2)  p1 + a1 p3 + a2 p2 − b² p2 p3 / r = 0
// and the stabilizing solution takes the roots that make the closed-loop companion coefficients
// a1 − b² p2 / r and a2 − b² p3 / r negative:
//     p2 = r (a1 + sqrt(a1² + b² q1 / r)) / b²
//     p3 = r (a2 + sqrt(a2² + b² (2 p2 + q2) / r)) / b²
//     p1 = b² p2 p3 / r − a1 p3 − a2 p2.
class CompanionPlant final : public SdcPlant {
 public:
  int state_dim() const override { return 2; }
  int input_dim() const override { return 1; }

  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override;
  void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;

  // The stabilizing SDRE solution P(x) for Q = diag(q1, q2), R = r (closed form above).
  static Eigen::Matrix2d sdre_solution(const Eigen::Vector2d& x, double q1, double q2, double r);
};

// A generic n-state, m-input plant with fixed-seed random coefficients:
//
//     F(x; u) = A + x1 C + x2² D + γ tanh(u1) H,      B(x) = G + x1 E,      f(x, u) := F(x; u) x + B(x) u
//
// A, G ~ N(0, 1)/√n and N(0, 1) (stabilizable with probability one), C, D, E, H small
// (N(0, 0.3²)/√n). With γ = input_coupling ≠ 0 the coefficients depend on the input, as the
// helicopter's do through its rotor speed, which exercises a controller's fixed point.
class RandomSdcPlant final : public SdcPlant {
 public:
  RandomSdcPlant(int n, int m, std::uint64_t seed, double input_coupling = 0.0);

  int state_dim() const override { return static_cast<int>(A_.rows()); }
  int input_dim() const override { return static_cast<int>(G_.cols()); }
  bool sdc_depends_on_input() const override { return input_coupling_ != 0.0; }

  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override;
  void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;

 private:
  Eigen::MatrixXd A_, C_, D_, H_, G_, E_;
  double input_coupling_;
};

// A linear plant xdot = A x + B u (F = A, B constant): its finite-horizon LQR problem has an exact
// discrete-time solution, against which the optimal control transcription is checked.
class LinearPlant final : public SdcPlant {
 public:
  LinearPlant(Eigen::MatrixXd A, Eigen::MatrixXd B);

  int state_dim() const override { return static_cast<int>(A_.rows()); }
  int input_dim() const override { return static_cast<int>(B_.cols()); }
  const Eigen::MatrixXd& A() const { return A_; }
  const Eigen::MatrixXd& B() const { return B_; }

  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override;
  void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override;
  bool jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const override;

 private:
  Eigen::MatrixXd A_, B_;
};

}  // namespace thetad
