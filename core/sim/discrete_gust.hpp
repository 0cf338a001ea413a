#pragma once

#include <vector>

#include <Eigen/Core>

namespace thetad::sim {

// A discrete "1 - cosine" gust (docs/model.md §15.3): along one NED axis, from `start` (s) for
// `duration` (s), the wind  (amplitude / 2) (1 - cos(2π (t - start) / duration)), zero outside:
// it rises smoothly to `amplitude` (m/s, signed) at mid-duration and falls back to calm.
struct DiscreteGust {
  int axis = 0;  // 0 north, 1 east, 2 down
  double amplitude = 0.0;
  double start = 0.0;
  double duration = 1.0;

  // Throws thetad::Error naming the first field out of range.
  void validate() const;
};

// The sum of the gusts at time t (m/s, NED). Allocates nothing.
Eigen::Vector3d discrete_gust_wind(const std::vector<DiscreteGust>& gusts, double t);

}  // namespace thetad::sim
