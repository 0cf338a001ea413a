#include "tests/test_plants.hpp"

#include <cmath>
#include <random>
#include <utility>

#include "core/error.hpp"

namespace thetad {

void CompanionPlant::f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                       Eigen::Ref<Eigen::VectorXd> xdot) const {
  const double x1 = x[0], x2 = x[1];
  xdot[0] = x2;
  xdot[1] = -x1 + x1 * x1 * x1 - 0.5 * x2 + 0.3 * x1 * x2 * x2 + (1.0 + 0.5 * x1 * x1) * u[0];
}

void CompanionPlant::sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>&,
                         Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  const double x1 = x[0], x2 = x[1];
  F << 0.0, 1.0, -1.0 + x1 * x1, -0.5 + 0.3 * x1 * x2;
  B << 0.0, 1.0 + 0.5 * x1 * x1;
}

Eigen::Matrix2d CompanionPlant::sdre_solution(const Eigen::Vector2d& x, double q1, double q2, double r) {
  const double x1 = x[0], x2 = x[1];
  const double a1 = -1.0 + x1 * x1, a2 = -0.5 + 0.3 * x1 * x2, b2 = std::pow(1.0 + 0.5 * x1 * x1, 2);
  const double p2 = r * (a1 + std::sqrt(a1 * a1 + b2 * q1 / r)) / b2;
  const double p3 = r * (a2 + std::sqrt(a2 * a2 + b2 * (2.0 * p2 + q2) / r)) / b2;
  const double p1 = b2 * p2 * p3 / r - a1 * p3 - a2 * p2;
  Eigen::Matrix2d P;
  P << p1, p2, p2, p3;
  return P;
}

RandomSdcPlant::RandomSdcPlant(int n, int m, std::uint64_t seed, double input_coupling)
    : input_coupling_(input_coupling) {
  if (n < 2 || m < 1) throw Error("RandomSdcPlant: needs n >= 2 states and m >= 1 inputs");
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto draw = [&](int rows, int cols, double scale) {
    Eigen::MatrixXd M(rows, cols);
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < rows; ++i) M(i, j) = scale * normal(rng);
    return M;
  };
  const double root_n = std::sqrt(static_cast<double>(n));
  A_ = draw(n, n, 1.0 / root_n);
  C_ = draw(n, n, 0.3 / root_n);
  D_ = draw(n, n, 0.3 / root_n);
  H_ = draw(n, n, 0.3 / root_n);
  G_ = draw(n, m, 1.0);
  E_ = draw(n, m, 0.3 / root_n);
}

void RandomSdcPlant::f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                       Eigen::Ref<Eigen::VectorXd> xdot) const {
  // Defined through the SDC form (a test plant: temporaries are fine here).
  xdot.noalias() = (A_ + x[0] * C_ + x[1] * x[1] * D_ + input_coupling_ * std::tanh(u[0]) * H_) * x;
  xdot.noalias() += (G_ + x[0] * E_) * u;
}

void RandomSdcPlant::sdc(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                         Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  F = A_ + x[0] * C_ + x[1] * x[1] * D_ + input_coupling_ * std::tanh(u[0]) * H_;
  B = G_ + x[0] * E_;
}

LinearPlant::LinearPlant(Eigen::MatrixXd A, Eigen::MatrixXd B) : A_(std::move(A)), B_(std::move(B)) {
  if (A_.rows() != A_.cols() || B_.rows() != A_.rows()) throw Error("LinearPlant: A must be n x n and B n x m");
}

void LinearPlant::f(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& u,
                    Eigen::Ref<Eigen::VectorXd> xdot) const {
  xdot.noalias() = A_ * x;
  xdot.noalias() += B_ * u;
}

void LinearPlant::sdc(const Eigen::Ref<const Eigen::VectorXd>&, const Eigen::Ref<const Eigen::VectorXd>&,
                      Eigen::Ref<Eigen::MatrixXd> F, Eigen::Ref<Eigen::MatrixXd> B) const {
  F = A_;
  B = B_;
}

bool LinearPlant::jacobian(const Eigen::Ref<const Eigen::VectorXd>&, const Eigen::Ref<const Eigen::VectorXd>&,
                           Eigen::Ref<Eigen::MatrixXd> dfdx, Eigen::Ref<Eigen::MatrixXd> dfdu) const {
  dfdx = A_;
  dfdu = B_;
  return true;
}

}  // namespace thetad
