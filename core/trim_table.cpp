#include "core/trim_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "core/error.hpp"
#include "core/grid_bracket.hpp"

namespace thetad {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kSame = 1e-9;  // m/s, rad: rounding of the reference's derivatives
// The blend's rate along the commanded acceleration a is taken as (blend(v + h a) − blend(v − h a)) / 2h:
// the exact directional derivative inside a grid cell, the mean of the two cells' on a grid line.
constexpr double kRateStep = 1e-3;  // s

}  // namespace

TrimTable::TrimTable(const heli::Helicopter& model, TrimGridAxes axes) : axes_(std::move(axes)) {
  const std::size_t points = axes_.speeds.size() * axes_.courses.size() * axes_.climb_rates.size();
  states_.resize(points);
  inputs_.resize(points);
  sweep_trims(model, axes_, [&](std::size_t i, std::size_t j, std::size_t k, const GridTrim& found) {
    const std::size_t index = (i * axes_.courses.size() + j) * axes_.climb_rates.size() + k;
    states_[index] = found.trim.state;
    inputs_[index] = found.trim.input;
  });
}

TrimGridAxes TrimTable::axes_covering(const ReferenceTrajectory& reference, double duration, double period) {
  double fastest = 0.0, lowest_climb = 0.0, highest_climb = 0.0;
  bool course_changes = false, moving = false;
  double course = 0.0;
  const auto samples = static_cast<long long>(std::llround(duration / period));
  for (long long k = 0; k <= samples; ++k) {
    const double t = static_cast<double>(k) * period;
    const Eigen::Vector3d velocity = reference.velocity(t);
    const double speed = std::hypot(velocity.x(), velocity.y());
    if (speed > envelope_speeds().back() + kSame) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "trims: the reference commands %.3g m/s of ground speed at t = %.3f s, beyond the trims' 20 m/s",
                    speed, t);
      throw Error(text);
    }
    fastest = std::max(fastest, speed);
    lowest_climb = std::min(lowest_climb, -velocity.z());
    highest_climb = std::max(highest_climb, -velocity.z());
    if (speed > kSame) {
      const double c = std::atan2(velocity.y(), velocity.x());
      if (moving && std::abs(std::remainder(c - course, kTwoPi)) > 1e-6) course_changes = true;
      if (!moving) course = c < 0.0 ? c + kTwoPi : c;
      moving = true;
    }
  }
  TrimGridAxes axes;
  for (const double speed : envelope_speeds()) {
    axes.speeds.push_back(speed);
    if (speed >= fastest - kSame) break;
  }
  if (course_changes)
    for (int j = 0; j < kEnvelopeCourses; ++j) axes.courses.push_back(kTwoPi * j / kEnvelopeCourses);
  else
    axes.courses = {course >= kTwoPi ? 0.0 : course};
  if (lowest_climb < -kSame) axes.climb_rates.push_back(lowest_climb);
  axes.climb_rates.push_back(0.0);
  if (highest_climb > kSame) axes.climb_rates.push_back(highest_climb);
  return axes;
}

void TrimTable::blend(const Eigen::Vector3d& velocity, State& state, Input& input) const {
  const GridBracket s = bracket(axes_.speeds, std::hypot(velocity.x(), velocity.y()));
  const GridBracket c = periodic_bracket(axes_.courses, std::atan2(velocity.y(), velocity.x()));
  const GridBracket h = bracket(axes_.climb_rates, -velocity.z());
  state.setZero();
  input.setZero();
  for_each_corner(s, c, h, [&](std::size_t i, std::size_t j, std::size_t k, double weight) {
    const std::size_t index = (i * axes_.courses.size() + j) * axes_.climb_rates.size() + k;
    state.noalias() += weight * states_[index];
    input.noalias() += weight * inputs_[index];
  });
}

void TrimTable::trim(const Reference& reference, TrimPoint& point) const {
  State state, ahead, behind;
  Input input, unused;
  blend(reference.velocity, state, input);
  point.state = state;
  point.input = input;
  if (reference.acceleration.isZero(0.0)) {
    point.rate.setZero();
    return;
  }
  blend(reference.velocity + kRateStep * reference.acceleration, ahead, unused);
  blend(reference.velocity - kRateStep * reference.acceleration, behind, unused);
  point.rate = (ahead - behind) / (2.0 * kRateStep);
}

std::string TrimTable::describe() const {
  std::ostringstream text;
  text << "helicopter trims at heading 0 over speeds [";
  for (std::size_t i = 0; i < axes_.speeds.size(); ++i) text << (i ? ", " : "") << axes_.speeds[i];
  text << "] m/s x " << axes_.courses.size() << " course(s) x climb rates [";
  for (std::size_t i = 0; i < axes_.climb_rates.size(); ++i) text << (i ? ", " : "") << axes_.climb_rates[i];
  text << "] m/s (Ipopt), blended on the commanded velocity";
  return text.str();
}

std::shared_ptr<const TrimSource> heli::Helicopter::trim_source(const ReferenceTrajectory& reference, double duration,
                                                               double period) const {
  return std::make_shared<TrimTable>(*this, TrimTable::axes_covering(reference, duration, period));
}

}  // namespace thetad
