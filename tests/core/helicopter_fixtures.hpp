#pragma once

// What the helicopter's tests share: fixed-size names for its vectors and matrices, the nominal
// parameters and the state at rest on the ground.
#include <Eigen/Core>

#include "core/helicopter/helicopter.hpp"

namespace thetad::heli::testing {

using Vector18 = Eigen::Matrix<double, kStateDim, 1>;
using Vector5 = Eigen::Matrix<double, kInputDim, 1>;
using Matrix18 = Eigen::Matrix<double, kStateDim, kStateDim>;
using Matrix18x5 = Eigen::Matrix<double, kStateDim, kInputDim>;

inline const Parameters kNominal = Parameters::nominal();

// Level, at rest on the ground, s = 1.
inline Eigen::VectorXd rest_state() {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kStateDim);
  x[kS] = 1.0;
  return x;
}

}  // namespace thetad::heli::testing
