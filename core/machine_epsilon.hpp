#pragma once

#include <limits>

namespace thetad {

// The spacing of doubles at 1: the unit every residual, conditioning and convergence tolerance of
// the solvers is a multiple of.
inline constexpr double kEps = std::numeric_limits<double>::epsilon();

}  // namespace thetad
