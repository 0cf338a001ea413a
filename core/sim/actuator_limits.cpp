#include "core/sim/actuator_limits.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"

namespace thetad::sim {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr const char* kChannelNames[heli::kInputDim] = {"T_mr", "delta_ped", "delta_col", "delta_lon", "delta_lat"};

// No published range for the pedal and the cyclic: twice the largest |trim| over the flight the
// lqr-scheduled envelope holds along the body axis (courses 0° and 180°, 0-20 m/s) and at low speed
// in every direction (<= 4 m/s), climb -1...1 m/s, resolved preset, nominal parameters; rounded up
// to 0.01 rad. One bound for both cyclics (a swashplate tilts as far either way). Beyond this set,
// sideways at 10-20 m/s, the A4 rotor speed collapses to 30-75 rad/s and the trims need up
// to 0.9 rad of cyclic, no servo range. actuator_limits_test recomputes both from fresh trims.
constexpr double kPedalBound = 0.40;
constexpr double kCyclicBound = 0.49;

}  // namespace

ActuatorLimits ActuatorLimits::x_cell(const heli::Parameters& p) {
  using namespace heli;
  ActuatorLimits limits;
  limits.lower[kTmr] = 0.0;
  limits.upper[kTmr] = p.max_main_rotor_thrust();
  limits.lower[kPed] = -kPedalBound;
  limits.upper[kPed] = kPedalBound;
  limits.lower[kCol] = -6.0 * kDegree - p.collective_trim_offset;
  limits.upper[kCol] = 10.0 * kDegree - p.collective_trim_offset;
  limits.lower[kLon] = -kCyclicBound;
  limits.upper[kLon] = kCyclicBound;
  limits.lower[kLat] = -kCyclicBound;
  limits.upper[kLat] = kCyclicBound;
  limits.rate = (limits.upper - limits.lower) / kFullRangeTime;
  return limits;
}

ActuatorLimits ActuatorLimits::off() {
  ActuatorLimits limits = x_cell();
  limits.enabled = false;
  return limits;
}

void ActuatorLimits::validate() const {
  for (int k = 0; k < heli::kInputDim; ++k) {
    const std::string channel = std::string("actuator limits: ") + kChannelNames[k];
    if (!std::isfinite(lower[k]) || !std::isfinite(upper[k]) || !(lower[k] < upper[k]))
      throw Error(channel + ": the bounds must be finite with lower < upper (lower " + std::to_string(lower[k]) +
                  ", upper " + std::to_string(upper[k]) + ")");
    if (!(rate[k] > 0.0) || !std::isfinite(rate[k]))
      throw Error(channel + ": the rate limit must be positive and finite (" + std::to_string(rate[k]) + ")");
  }
}

ActuatorLimiter::ActuatorLimiter(const ActuatorLimits& limits, double period)
    : limits_(limits), step_(limits.rate * period) {}

void ActuatorLimiter::reset() {
  first_ = true;
  last_flags_ = 0;
  counts_ = SaturationCounts::none(heli::kInputDim);
}

void ActuatorLimiter::apply(Eigen::Ref<Eigen::VectorXd> input) {
  last_flags_ = 0;
  if (!limits_.enabled) return;
  for (int k = 0; k < heli::kInputDim; ++k) {
    double low = limits_.lower[k], high = limits_.upper[k];
    if (!first_) {
      // previous_ lies in [lower, upper], so this window is never empty.
      low = std::max(low, previous_[k] - step_[k]);
      high = std::min(high, previous_[k] + step_[k]);
    }
    const double limited = std::clamp(input[k], low, high);
    if (limited != input[k]) {
      if (limited == limits_.lower[k] || limited == limits_.upper[k]) {
        last_flags_ |= 1u << k;
        ++counts_.magnitude[k];
      } else {
        last_flags_ |= 1u << (k + heli::kInputDim);
        ++counts_.rate[k];
      }
    }
    input[k] = limited;
  }
  previous_ = input;
  first_ = false;
  if (last_flags_ != 0) ++counts_.samples_limited;
}

}  // namespace thetad::sim
