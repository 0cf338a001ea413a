#include "core/tora_plant.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace thetad {

ToraPlant::ToraPlant(double epsilon) : epsilon_(epsilon) {
  if (!(epsilon > 0.0 && epsilon < 1.0))
    throw Error("tora: epsilon must lie in (0, 1), got " + std::to_string(epsilon));
}

void ToraPlant::f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                  Eigen::Ref<Eigen::VectorXd> xdot) const {
  const double e = epsilon_, s = std::sin(x[2]), c = std::cos(x[2]);
  const double d = 1.0 - e * e * c * c;
  xdot[0] = x[1];
  xdot[1] = (-x[0] + e * x[3] * x[3] * s - e * c * u[0]) / d;
  xdot[2] = x[3];
  xdot[3] = (e * c * (x[0] - e * x[3] * x[3] * s) + u[0]) / d;
}

void ToraPlant::sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>&,
                    Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  const double e = epsilon_, s = std::sin(x[2]), c = std::cos(x[2]);
  const double d = 1.0 - e * e * c * c;
  F.setZero();
  B.setZero();
  F(0, 1) = 1.0;
  F(1, 0) = -1.0 / d;
  F(1, 3) = e * x[3] * s / d;
  F(2, 3) = 1.0;
  F(3, 0) = e * c / d;
  F(3, 3) = -e * e * c * s * x[3] / d;
  B(1, 0) = -e * c / d;
  B(3, 0) = 1.0 / d;
}

bool ToraPlant::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                         Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const {
  const double e = epsilon_, s = std::sin(x[2]), c = std::cos(x[2]), w = x[3];
  const double d = 1.0 - e * e * c * c, dd = 2.0 * e * e * c * s;  // dD/dθ
  const double n2 = -x[0] + e * w * w * s - e * c * u[0];
  const double n4 = e * c * (x[0] - e * w * w * s) + u[0];
  dfdx.setZero();
  dfdu.setZero();
  dfdx(0, 1) = 1.0;
  dfdx(1, 0) = -1.0 / d;
  dfdx(1, 2) = (e * w * w * c + e * s * u[0]) / d - n2 * dd / (d * d);
  dfdx(1, 3) = 2.0 * e * w * s / d;
  dfdx(2, 3) = 1.0;
  dfdx(3, 0) = e * c / d;
  dfdx(3, 2) = (-e * s * x[0] - e * e * w * w * (c * c - s * s)) / d - n4 * dd / (d * d);
  dfdx(3, 3) = -2.0 * e * e * c * s * w / d;
  dfdu(1, 0) = -e * c / d;
  dfdu(3, 0) = 1.0 / d;
  return true;
}

std::vector<LogColumn> ToraPlant::state_columns() const {
  return {{"xi", ""}, {"xi_dot", ""}, {"theta", "rad"}, {"theta_dot", "rad_per_s"}};
}

std::vector<LogColumn> ToraPlant::input_columns() const { return {{"torque", ""}}; }

}  // namespace thetad
