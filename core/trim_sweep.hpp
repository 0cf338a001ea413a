#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "core/trim.hpp"

namespace thetad {

// The helicopter's trims over a grid of straight flights at heading 0 (ground speed, course from
// the nose, climb rate; docs/lqr-scheduled.md), one sweep up the speeds per course and climb rate:
// the last trim is Ipopt's initial guess for the next, and where the model's own rotor-speed model
// (A4) has no trim (high speed: Ω collapses, docs/model.md §11) the governor's is used, for
// the rest of the sweep, since A4's Ω falls monotonically with speed. At speed 0 the course means
// nothing: the first course's trim serves every course, which keeps a blend continuous through
// the origin, where the course of a commanded velocity jumps.
struct TrimGridAxes {
  std::vector<double> speeds;       // m/s, ascending, >= 0
  std::vector<double> courses;      // rad, ascending in [0, 2π)
  std::vector<double> climb_rates;  // m/s, up positive, ascending
  double altitude = 0.0;            // of the trims (m); the model does not depend on it
};

// The envelope the scheduled LQR and the feed-forward trims are designed over: ground speeds
// 0 … 20 m/s, closer where the trims change fastest (low speed), and kEnvelopeCourses courses,
// every 45°.
std::vector<double> envelope_speeds();
inline constexpr int kEnvelopeCourses = 8;

// One trim of the grid and the model it was found on (the helicopter's own, or its governor twin).
struct GridTrim {
  const Trim& trim;
  const heli::Helicopter& plant;
};

// Calls visit(speed index, course index, climb index, trim) for every point, climb rates outermost,
// then courses, then speeds. Throws thetad::Error naming the point where neither rotor model has a
// trim.
void sweep_trims(const heli::Helicopter& model, const TrimGridAxes& axes,
                 const std::function<void(std::size_t, std::size_t, std::size_t, const GridTrim&)>& visit);

}  // namespace thetad
