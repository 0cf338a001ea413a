#include "controllers/linearization.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace thetad {

Linearization linearize(const SdcPlant& plant, const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                        double relative_step) {
  const Eigen::Index n = plant.state_dim(), m = plant.input_dim();
  if (x.size() != n || u.size() != m) {
    throw Error("linearize: state and input have " + std::to_string(x.size()) + " and " + std::to_string(u.size()) +
                " entries, the plant " + std::to_string(n) + " and " + std::to_string(m));
  }
  Linearization result{Eigen::MatrixXd(n, n), Eigen::MatrixXd(n, m)};
  Eigen::VectorXd z(n + m), forward(n), backward(n);
  z << x, u;
  for (Eigen::Index j = 0; j < n + m; ++j) {
    const double h = relative_step * std::max(1.0, std::abs(z(j)));
    const double saved = z(j);
    z(j) = saved + h;
    plant.f(z.head(n), z.tail(m), forward);
    z(j) = saved - h;
    plant.f(z.head(n), z.tail(m), backward);
    z(j) = saved;
    (j < n ? result.A.col(j) : result.B.col(j - n)) = (forward - backward) / (2.0 * h);
  }
  return result;
}

OperatingPoint operating_point(const heli::Helicopter& model, const Trim& trim) {
  Reference reference;
  reference.position = trim.state.segment<3>(heli::kXp);
  reference.integral = trim.state.segment<3>(heli::kXi);
  Eigen::VectorXd tracking(model.state_dim());
  model.tracking_vector(trim.state, reference, tracking);
  return {trim.state, trim.input, tracking};
}

CareResult design_lqr(const SdcPlant& plant, const OperatingPoint& point, const Eigen::MatrixXd& Q,
                      const Eigen::MatrixXd& R, Eigen::Index design_states) {
  const Eigen::Index n = plant.state_dim();
  if (design_states < 1 || design_states > n) {
    throw Error("design_lqr: design_states must be in [1, " + std::to_string(n) + "], got " +
                std::to_string(design_states));
  }
  if (Q.rows() != n || Q.cols() != n) {
    throw Error("design_lqr: Q is " + std::to_string(Q.rows()) + "x" + std::to_string(Q.cols()) +
                ", the plant needs " + std::to_string(n) + "x" + std::to_string(n));
  }
  const Linearization linear = linearize(plant, point.state, point.input);
  const Eigen::Index k = design_states;
  return solve_care(linear.A.topLeftCorner(k, k), linear.B.topRows(k), Q.topLeftCorner(k, k), R);
}

}  // namespace thetad
