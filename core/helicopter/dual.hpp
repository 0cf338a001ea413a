#pragma once

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "core/helicopter/state.hpp"

namespace thetad::heli {

// A number with its derivatives with respect to the 18 states and the 5 inputs (forward-mode
// automatic differentiation by Eigen's AutoDiff): Helicopter::jacobian evaluates the equations of
// motion in it. Fixed-size derivatives, so that arithmetic on it allocates nothing.
using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, kStateDim + kInputDim, 1>>;
using DualState = Eigen::Matrix<Dual, kStateDim, 1>;
using DualInput = Eigen::Matrix<Dual, kInputDim, 1>;

// The value of a number the equations of motion are evaluated in (for guards and messages).
inline double value_of(double x) { return x; }
inline double value_of(const Dual& x) { return x.value(); }

}  // namespace thetad::heli
