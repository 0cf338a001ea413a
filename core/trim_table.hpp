#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/feedforward.hpp"
#include "core/trim_sweep.hpp"

namespace thetad {

// The helicopter's trim source (docs/model.md §7.1): Ipopt trims of straight flight at heading 0
// over a grid of ground speed, course and climb rate (sweep_trims), blended multilinearly at the
// commanded velocity (clamped at the grid's edges, periodic in course), and the blend's rate of
// change along the commanded acceleration. Every controller of a flight reads the same table.
class TrimTable final : public TrimSource {
 public:
  // Finds the trims now: ~11 ms of Ipopt per point. Throws thetad::Error naming the point where
  // the helicopter has no trim.
  TrimTable(const heli::Helicopter& model, TrimGridAxes axes);

  // The smallest grid that holds every velocity `reference` commands at its samples (every
  // `period` s over `duration` s): the scheduled LQR's envelope speeds (0 … 20 m/s) up to the
  // first at or above the fastest command; its eight courses where the commanded course changes,
  // else that one course; the climb rates {lowest, 0, highest} commanded. Throws thetad::Error
  // naming the time and the speed where the reference is faster than 20 m/s.
  static TrimGridAxes axes_covering(const ReferenceTrajectory& reference, double duration, double period);

  // Allocates nothing.
  void trim(const Reference& reference, TrimPoint& point) const override;
  std::string describe() const override;
  const TrimGridAxes& axes() const { return axes_; }

 private:
  using State = Eigen::Matrix<double, heli::kStateDim, 1>;
  using Input = Eigen::Matrix<double, heli::kInputDim, 1>;
  void blend(const Eigen::Vector3d& velocity, State& state, Input& input) const;

  TrimGridAxes axes_;
  // Point (speed i, course j, climb k) at (i · courses + j) · climb_rates + k.
  std::vector<State> states_;
  std::vector<Input> inputs_;
};

}  // namespace thetad
