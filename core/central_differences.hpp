#pragma once

// Central differences of a vector function: the yardstick for exact derivatives in the tests, and
// the derivatives of a plant that gives no Jacobian where one is needed (thetad optimal).
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <Eigen/Core>

namespace thetad {

// d g / d z at z (q x p) with the step h max(1, |z_j|), h = eps^(1/3) by default: O(h^2) where g is
// smooth, plus g's rounding over h.
inline Eigen::MatrixXd central_differences(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& g,
                                           const Eigen::VectorXd& z,
                                           double h = std::cbrt(std::numeric_limits<double>::epsilon())) {
  Eigen::MatrixXd derivative;
  for (Eigen::Index j = 0; j < z.size(); ++j) {
    Eigen::VectorXd plus = z, minus = z;
    const double step = h * std::max(1.0, std::abs(z[j]));
    plus[j] += step;
    minus[j] -= step;
    const Eigen::VectorXd difference = (g(plus) - g(minus)) / (plus[j] - minus[j]);
    if (j == 0) derivative.resize(difference.size(), z.size());
    derivative.col(j) = difference;
  }
  return derivative;
}

}  // namespace thetad
