#pragma once

// A one-state, one-input SdcPlant xdot = a(x) x + b(x, u) u whose SDRE has a closed form:
// 2 a P − P² b² / r + q = 0 gives P = r (a + sqrt(a² + b² q / r)) / b².

#include <cmath>
#include <functional>
#include <utility>

#include <Eigen/Core>

#include "controllers/sdre.hpp"
#include "core/sdc_plant.hpp"

namespace thetad::testing {

class ScalarPlant final : public SdcPlant {
 public:
  ScalarPlant(std::function<double(double)> a, std::function<double(double, double)> b, bool input_dependent)
      : a_(std::move(a)), b_(std::move(b)), input_dependent_(input_dependent) {}

  int state_dim() const override { return 1; }
  int input_dim() const override { return 1; }
  bool sdc_depends_on_input() const override { return input_dependent_; }
  using SdcPlant::f;
  using SdcPlant::sdc;
  void f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
         Eigen::Ref<Eigen::VectorXd> xdot) const override {
    xdot(0) = a_(x(0)) * x(0) + b_(x(0), u(0)) * u(0);
  }
  void sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
           Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const override {
    F(0, 0) = a_(x(0));
    B(0, 0) = b_(x(0), u(0));
  }

  // The SDRE solution at (x; u) for weights q, r.
  double riccati(double x, double u, double q, double r) const {
    const double a = a_(x), b = b_(x, u);
    return r * (a + std::sqrt(a * a + b * b * q / r)) / (b * b);
  }

 private:
  std::function<double(double)> a_;
  std::function<double(double, double)> b_;
  bool input_dependent_;
};

// The SDRE's input at time t and state x on a ScalarPlant.
inline double sdre_control_at(SdreController& sdre, double t, double x) {
  Eigen::VectorXd u(1);
  sdre.control(t, Eigen::VectorXd::Constant(1, x), Reference{}, u);
  return u(0);
}

}  // namespace thetad::testing
