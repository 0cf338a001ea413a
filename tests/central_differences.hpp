#pragma once

// Central differences of a vector function, the yardstick for exact derivatives in the tests.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <Eigen/Core>

namespace thetad::testing {

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

// The largest difference of two matrices, relative to the largest entry of its row in `reference`:
// a plant's rows differ in scale by orders of magnitude.
inline double row_relative_error(const Eigen::MatrixXd& exact, const Eigen::MatrixXd& reference) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < exact.rows(); ++i) {
    const double scale = std::max(1e-12, reference.row(i).cwiseAbs().maxCoeff());
    worst = std::max(worst, (exact.row(i) - reference.row(i)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

}  // namespace thetad::testing
