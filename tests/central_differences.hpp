#pragma once

// The yardsticks for exact derivatives in the tests: central differences (core/central_differences.hpp)
// and a row-relative comparison.
#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "core/central_differences.hpp"

namespace thetad::testing {

using thetad::central_differences;

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
