// A user's program: solves a double-integrator LQR problem through the installed thetad.
#include <Eigen/Dense>
#include <cstdio>

#include "core/riccati.hpp"

int main() {
  Eigen::Matrix2d a{{0.0, 1.0}, {0.0, 0.0}};
  Eigen::Vector2d b{0.0, 1.0};
  const auto result = thetad::solve_care(a, b, Eigen::Matrix2d::Identity(), Eigen::Matrix<double, 1, 1>::Identity());
  // Known solution: P = [[sqrt(3), 1], [1, sqrt(3)]].
  const double error = std::abs(result.P(0, 0) - std::sqrt(3.0)) + std::abs(result.P(0, 1) - 1.0);
  std::printf("downstream: P(0,0) = %.12f, residual %.2e\n", result.P(0, 0), result.relative_residual);
  return error < 1e-10 ? 0 : 1;
}
