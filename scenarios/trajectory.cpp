#include "scenarios/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace thetad {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// C++20 deduces this for an aggregate by itself; Clang 14 does not implement that yet.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

void require_period(const std::string& phase, const char* type, double period) {
  if (!(period > 0.0) || !std::isfinite(period))
    throw Error("phase '" + phase + "' (" + type + "): period must be positive and finite");
}

void require_finite(const std::string& phase, const char* type, const char* what, double value) {
  if (!std::isfinite(value)) throw Error("phase '" + phase + "' (" + type + "): " + what + " must be finite");
}

void validate(const std::string& phase, const Motion& motion) {
  const char* type = motion_type(motion);
  const auto finite_vector = [&](const char* what, const Eigen::Vector3d& v) {
    if (!v.allFinite()) throw Error("phase '" + phase + "' (" + type + "): " + what + " must be finite");
  };
  std::visit(Overloaded{
                 [](const Hold&) {},
                 [&](const Ramp& m) { finite_vector("target", m.to); },
                 [&](const Step& m) { finite_vector("target", m.to); },
                 [&](const Blend& m) { finite_vector("target", m.to); },
                 [&](const Accelerate& m) {
                   if (!(std::abs(m.direction.norm() - 1.0) < 1e-9))
                     throw Error("phase '" + phase + "' (" + type + "): direction must be a unit vector");
                   require_finite(phase, type, "start_speed", m.start_speed);
                   require_finite(phase, type, "end_speed", m.end_speed);
                 },
                 [&](const Sinusoid& m) {
                   finite_vector("amplitude", m.amplitude);
                   require_period(phase, type, m.period);
                 },
                 [&](const FigureEight& m) {
                   require_finite(phase, type, "amplitude_x", m.amplitude_x);
                   require_finite(phase, type, "amplitude_y", m.amplitude_y);
                   require_period(phase, type, m.period);
                 },
                 [&](const Circle& m) {
                   require_finite(phase, type, "radius", m.radius);
                   require_finite(phase, type, "descent", m.descent);
                   require_period(phase, type, m.period);
                 },
             },
             motion);
}

// `motion` on a clock running `s` times faster. Hold, Ramp, Step and Blend are shaped by the
// fraction of their phase, which the phase's shorter duration scales by itself.
Motion on_faster_clock(const Motion& motion, double s) {
  return std::visit(Overloaded{
                        [&](Accelerate m) -> Motion {
                          m.start_speed *= s;
                          m.end_speed *= s;
                          return m;
                        },
                        [&](Sinusoid m) -> Motion {
                          m.period /= s;
                          return m;
                        },
                        [&](FigureEight m) -> Motion {
                          m.period /= s;
                          return m;
                        },
                        [&](Circle m) -> Motion {
                          m.period /= s;
                          return m;
                        },
                        [](const auto& m) -> Motion { return m; },
                    },
                    motion);
}

}  // namespace

Eigen::Vector3d Hold::position(const Eigen::Vector3d& start, double, double) const { return start; }
Derivatives Hold::derivatives(const Eigen::Vector3d&, double, double) const { return {}; }

Eigen::Vector3d Ramp::position(const Eigen::Vector3d& start, double tau, double duration) const {
  const double fraction = std::clamp(tau / duration, 0.0, 1.0);
  return start + fraction * (to - start);
}

Derivatives Ramp::derivatives(const Eigen::Vector3d& start, double, double duration) const {
  return {(to - start) / duration, Eigen::Vector3d::Zero()};
}

Eigen::Vector3d Step::position(const Eigen::Vector3d&, double, double) const { return to; }
Derivatives Step::derivatives(const Eigen::Vector3d&, double, double) const { return {}; }

Eigen::Vector3d Blend::position(const Eigen::Vector3d& start, double tau, double duration) const {
  const double sigma = std::clamp(tau / duration, 0.0, 1.0);
  const double s = sigma * sigma * sigma * (10.0 + sigma * (-15.0 + 6.0 * sigma));
  return start + s * (to - start);
}

Derivatives Blend::derivatives(const Eigen::Vector3d& start, double tau, double duration) const {
  const double sigma = std::clamp(tau / duration, 0.0, 1.0);
  // s'(σ) = 30σ² − 60σ³ + 30σ⁴, s''(σ) = 60σ − 180σ² + 120σ³, and dσ/dt = 1/duration.
  const double rate = 30.0 * sigma * sigma * (1.0 + sigma * (-2.0 + sigma));
  const double curvature = 60.0 * sigma * (1.0 + sigma * (-3.0 + 2.0 * sigma));
  return {rate / duration * (to - start), curvature / (duration * duration) * (to - start)};
}

Eigen::Vector3d Accelerate::position(const Eigen::Vector3d& start, double tau, double duration) const {
  const double t = std::clamp(tau, 0.0, duration);
  return start + (start_speed * t + (end_speed - start_speed) * t * t / (2.0 * duration)) * direction;
}

Derivatives Accelerate::derivatives(const Eigen::Vector3d&, double tau, double duration) const {
  const double t = std::clamp(tau, 0.0, duration);
  return {(start_speed + (end_speed - start_speed) * t / duration) * direction,
          (end_speed - start_speed) / duration * direction};
}

Eigen::Vector3d Sinusoid::position(const Eigen::Vector3d& start, double tau, double) const {
  return start + std::sin(kTwoPi * tau / period) * amplitude;
}

Derivatives Sinusoid::derivatives(const Eigen::Vector3d&, double tau, double) const {
  const double omega = kTwoPi / period, angle = omega * tau;
  return {omega * std::cos(angle) * amplitude, -omega * omega * std::sin(angle) * amplitude};
}

Eigen::Vector3d FigureEight::position(const Eigen::Vector3d& start, double tau, double) const {
  const double angle = kTwoPi * tau / period;
  return start + Eigen::Vector3d(amplitude_x * std::sin(angle), -amplitude_y * std::sin(2.0 * angle), 0.0);
}

Derivatives FigureEight::derivatives(const Eigen::Vector3d&, double tau, double) const {
  const double omega = kTwoPi / period, angle = omega * tau;
  return {omega * Eigen::Vector3d(amplitude_x * std::cos(angle), -2.0 * amplitude_y * std::cos(2.0 * angle), 0.0),
          omega * omega *
              Eigen::Vector3d(-amplitude_x * std::sin(angle), 4.0 * amplitude_y * std::sin(2.0 * angle), 0.0)};
}

Eigen::Vector3d Circle::position(const Eigen::Vector3d& start, double tau, double) const {
  const double angle = kTwoPi * tau / period;
  const double lateral = (counterclockwise ? 1.0 : -1.0) * radius * (1.0 - std::cos(angle));
  // Altitude h = h0 − (Δh/2)(1 − cos ωτ), so z = −h rises by the same amount.
  const double down = 0.5 * descent * (1.0 - std::cos(angle));
  return start + Eigen::Vector3d(radius * std::sin(angle), lateral, down);
}

Derivatives Circle::derivatives(const Eigen::Vector3d&, double tau, double) const {
  const double omega = kTwoPi / period, angle = omega * tau;
  const double side = counterclockwise ? 1.0 : -1.0;
  return {omega * Eigen::Vector3d(radius * std::cos(angle), side * radius * std::sin(angle),
                                  0.5 * descent * std::sin(angle)),
          omega * omega *
              Eigen::Vector3d(-radius * std::sin(angle), side * radius * std::cos(angle),
                              0.5 * descent * std::cos(angle))};
}

const char* motion_type(const Motion& motion) {
  return std::visit(Overloaded{
                        [](const Hold&) { return "hold"; },
                        [](const Ramp&) { return "ramp"; },
                        [](const Step&) { return "step"; },
                        [](const Blend&) { return "blend"; },
                        [](const Accelerate&) { return "accelerate"; },
                        [](const Sinusoid&) { return "sinusoid"; },
                        [](const FigureEight&) { return "figure8"; },
                        [](const Circle&) { return "circle"; },
                    },
                    motion);
}

Eigen::Vector3d PhasedTrajectory::Phase::position(double t) const {
  const double tau = std::clamp(t - start_time, 0.0, end_time - start_time);
  return std::visit([&](const auto& m) { return m.position(start_position, tau, end_time - start_time); }, motion);
}

Derivatives PhasedTrajectory::Phase::derivatives(double t) const {
  const double tau = std::clamp(t - start_time, 0.0, end_time - start_time);
  return std::visit([&](const auto& m) { return m.derivatives(start_position, tau, end_time - start_time); }, motion);
}

void PhasedTrajectory::append(std::string name, double end_time, const Motion& motion) {
  const double start_time = this->end_time();
  if (!(end_time > start_time) || !std::isfinite(end_time))
    throw Error("phase '" + name + "': must end after it starts (" + std::to_string(start_time) + " s), got " +
                std::to_string(end_time) + " s");
  validate(name, motion);
  // The phases are stored unturned: each starts where the previous one ended, as written.
  const Eigen::Vector3d start_position = phases_.empty() ? start_ : phases_.back().end_position();
  phases_.push_back({std::move(name), start_time, end_time, start_position, motion});
}

PhasedTrajectory PhasedTrajectory::time_scaled(double speed_scale) const {
  if (!(speed_scale > 0.0) || !std::isfinite(speed_scale))
    throw Error("trajectory speed scale " + std::to_string(speed_scale) + ": must be positive and finite");
  PhasedTrajectory scaled(start_);
  for (const Phase& phase : phases_)
    scaled.append(phase.name, phase.end_time / speed_scale, on_faster_clock(phase.motion, speed_scale));
  scaled.turned_ = turned_;
  scaled.turn_ = turn_;
  return scaled;
}

PhasedTrajectory PhasedTrajectory::turned(double course) const {
  if (!std::isfinite(course)) throw Error("trajectory course " + std::to_string(course) + ": must be finite");
  PhasedTrajectory result = *this;
  const double c = std::cos(course), s = std::sin(course);
  Eigen::Matrix3d turn;
  turn << c, -s, 0.0,  //
      s, c, 0.0,       //
      0.0, 0.0, 1.0;
  result.turn_ = turn * turn_;
  result.turned_ = true;
  return result;
}

Eigen::Vector3d PhasedTrajectory::turned_offset(const Eigen::Vector3d& position) const {
  return turned_ ? Eigen::Vector3d(start_ + turn_ * (position - start_)) : position;
}

const PhasedTrajectory::Phase* PhasedTrajectory::phase_at(double t) const {
  // The first phase whose end lies beyond t: a boundary belongs to the later phase, so a step
  // takes effect at its start time.
  const auto it = std::upper_bound(phases_.begin(), phases_.end(), t,
                                   [](double time, const Phase& phase) { return time < phase.end_time; });
  return it == phases_.end() ? nullptr : &*it;
}

Eigen::Vector3d PhasedTrajectory::position(double t) const {
  if (phases_.empty()) return start_;
  const Phase* phase = phase_at(t);
  return turned_offset(phase ? phase->position(t) : phases_.back().end_position());
}

Derivatives PhasedTrajectory::derivatives(double t) const {
  const Phase* phase = phase_at(t);
  if (!phase || t < 0.0) return {};
  Derivatives d = phase->derivatives(t);
  if (turned_) {
    d.velocity = turn_ * d.velocity;
    d.acceleration = turn_ * d.acceleration;
  }
  return d;
}

}  // namespace thetad
