#include "core/sim/discrete_gust.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace thetad::sim {

void DiscreteGust::validate() const {
  if (axis < 0 || axis > 2) throw Error("discrete gust: the axis must be north (0), east (1) or down (2)");
  if (!std::isfinite(amplitude)) throw Error("discrete gust: the amplitude must be finite");
  if (!(start >= 0.0) || !std::isfinite(start)) throw Error("discrete gust: the start must be finite and >= 0");
  if (!(duration > 0.0) || !std::isfinite(duration)) throw Error("discrete gust: the duration must be positive and finite");
}

Eigen::Vector3d discrete_gust_wind(const std::vector<DiscreteGust>& gusts, double t) {
  Eigen::Vector3d wind = Eigen::Vector3d::Zero();
  for (const DiscreteGust& gust : gusts) {
    const double phase = (t - gust.start) / gust.duration;
    if (phase < 0.0 || phase > 1.0) continue;
    wind[gust.axis] += 0.5 * gust.amplitude * (1.0 - std::cos(2.0 * std::numbers::pi * phase));
  }
  return wind;
}

}  // namespace thetad::sim
