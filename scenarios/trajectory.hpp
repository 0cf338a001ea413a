#pragma once

#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "core/control_law.hpp"

namespace thetad {

// Trajectory primitives (docs/model.md §10: "combinations of ramps, sinusoidal waves, and step inputs in
// three directions"; §8.4). Each one is a motion relative to where its phase starts: it gets the
// start position, the time since the phase began (tau) and the phase's duration, and returns the
// commanded position. Positions are NED (z down, altitude h = -z); the scenario files speak of h
// and the loader converts. A motion that starts at its start position (all but Step) keeps the
// command continuous at the phase boundary; velocity jumps there are intended (docs/model.md §10).

// The commanded velocity and acceleration of a motion (NED): its position's exact time derivatives.
struct Derivatives {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
};

// Stays at the start position.
struct Hold {
  Eigen::Vector3d position(const Eigen::Vector3d& start, double tau, double duration) const;
  Derivatives derivatives(const Eigen::Vector3d& start, double tau, double duration) const;
};

// Straight line at constant speed from the start to `to`, reached at the end of the phase.
struct Ramp {
  Eigen::Vector3d to = Eigen::Vector3d::Zero();
  Eigen::Vector3d position(const Eigen::Vector3d& start, double tau, double duration) const;
  Derivatives derivatives(const Eigen::Vector3d& start, double tau, double duration) const;
};

// Jumps to `to` at the start of the phase and stays there: the only deliberate discontinuity.
struct Step {
  Eigen::Vector3d to = Eigen::Vector3d::Zero();
  Eigen::Vector3d position(const Eigen::Vector3d& start, double tau, double duration) const;
  Derivatives derivatives(const Eigen::Vector3d& start, double tau, double duration) const;
};

// Quintic blend from the start to `to` over the phase: s(σ) = 10σ³ − 15σ⁴ + 6σ⁵, σ = tau/duration,
// so velocity and acceleration are zero at both ends (a smooth transition between two points).
struct Blend {
  Eigen::Vector3d to = Eigen::Vector3d::Zero();
  Eigen::Vector3d position(const Eigen::Vector3d& start, double tau, double duration) const;
  Derivatives derivatives(const Eigen::Vector3d& start, double tau, double duration) const;
};

// Along `direction` with the speed changing linearly from start_speed to end_speed over the phase
// (constant acceleration): start + direction (v0 tau + (v1 − v0) tau² / (2 duration)). Equal speeds
// cruise. Chaining phases with matching speeds keeps the commanded velocity continuous.
struct Accelerate {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // NED, unit length
  double start_speed = 0.0;                              // m/s
  double end_speed = 0.0;                                // m/s
  Eigen::Vector3d position(const Eigen::Vector3d& start, double tau, double duration) const;
  Derivatives derivatives(const Eigen::Vector3d& start, double tau, double duration) const;
};

// start + amplitude · sin(2π tau / period), per axis: back at the start after whole periods.
struct Sinusoid {
  Eigen::Vector3d amplitude = Eigen::Vector3d::Zero();  // NED (m)
  double period = 1.0;                                  // s
  Eigen::Vector3d position(const Eigen::Vector3d& start, double tau, double duration) const;
  Derivatives derivatives(const Eigen::Vector3d& start, double tau, double duration) const;
};

// The figure 8 of scenario I (docs/model.md §10): x = x0 + A_x sin(ωτ), y = y0 − A_y sin(2ωτ), ω = 2π/T8,
// at constant altitude. It crosses itself at the start point and moves first towards −y and +x;
// speed at the crossing ω·sqrt(A_x² + 4A_y²), at the lobe ends 2ωA_y.
struct FigureEight {
  double amplitude_x = 8.0;  // A_x (m)
  double amplitude_y = 4.0;  // A_y (m)
  double period = 50.0;      // T8 (s)
  Eigen::Vector3d position(const Eigen::Vector3d& start, double tau, double duration) const;
  Derivatives derivatives(const Eigen::Vector3d& start, double tau, double duration) const;
};

// The circle of scenario II (docs/model.md §10): x = x0 + R sin(ωτ), y = y0 ± R(1 − cos ωτ), ω = 2π/T_c,
// with the altitude dipping by `descent` at the half circle: h = h0 − (Δh/2)(1 − cos ωτ).
// Counterclockwise (+) means the polar angle about the centre (x0, y0 + R) increases, i.e.
// counterclockwise in an x-right / y-up plot: first motion +x, then +y. Speed Rω horizontally.
struct Circle {
  double radius = 15.0;    // R_c (m)
  double period = 60.0;    // T_c (s)
  double descent = 2.0;    // Δh (m): lowest point Δh below the start altitude
  bool counterclockwise = true;
  Eigen::Vector3d position(const Eigen::Vector3d& start, double tau, double duration) const;
  Derivatives derivatives(const Eigen::Vector3d& start, double tau, double duration) const;
};

using Motion = std::variant<Hold, Ramp, Step, Blend, Accelerate, Sinusoid, FigureEight, Circle>;

// The name of a motion's alternative as the scenario files spell it ("hold", "figure8", ...).
const char* motion_type(const Motion& motion);

// A piecewise-in-time command: phases back to back from t = 0, each a Motion that starts where the
// previous phase ended (the first where the trajectory starts). Before 0 it gives the first
// phase's value at its start, after the last phase the last phase's final position.
class PhasedTrajectory final : public ReferenceTrajectory {
 public:
  struct Phase {
    std::string name;
    double start_time = 0.0;
    double end_time = 0.0;
    Eigen::Vector3d start_position = Eigen::Vector3d::Zero();  // NED
    Motion motion;

    Eigen::Vector3d position(double t) const;
    Derivatives derivatives(double t) const;
    Eigen::Vector3d end_position() const { return position(end_time); }
  };

  explicit PhasedTrajectory(const Eigen::Vector3d& start = Eigen::Vector3d::Zero()) : start_(start) {}

  // Adds a phase from end_time() to `end_time`. Throws thetad::Error unless end_time > end_time()
  // and the motion's parameters are valid (positive, finite periods; finite positions).
  void append(std::string name, double end_time, const Motion& motion);

  // NED command; the hot path of the simulator: no allocation.
  Eigen::Vector3d position(double t) const override;
  // Its derivatives, those of the phase that holds t (a boundary belongs to the later phase);
  // zero before the start and from the last phase's end on, where the command holds still.
  Eigen::Vector3d velocity(double t) const override { return derivatives(t).velocity; }
  Eigen::Vector3d acceleration(double t) const override { return derivatives(t).acceleration; }
  Derivatives derivatives(double t) const;

  const std::vector<Phase>& phases() const { return phases_; }
  const Eigen::Vector3d& start_position() const { return start_; }
  // End of the last phase (0 without phases).
  double end_time() const { return phases_.empty() ? 0.0 : phases_.back().end_time; }
  Eigen::Vector3d end_position() const {
    return turned_offset(phases_.empty() ? start_ : phases_.back().end_position());
  }

  // The same path flown `speed_scale` times faster: r_s(t) = r(s t), so velocities are s times and
  // accelerations s² times the original's. Every phase ends at end_time / s, and each motion's
  // own clock follows (periods / s, Accelerate's speeds × s); the positions, targets and
  // amplitudes stay. Throws thetad::Error unless s is positive and finite.
  PhasedTrajectory time_scaled(double speed_scale) const;
  // The same trajectory turned by `course` (rad, clockwise seen from above: north towards east)
  // about the vertical through its start: a path that went north goes on that course, its
  // velocities and accelerations turned with it, the heights unchanged. Composes with earlier
  // turns and with time_scaled. Throws thetad::Error unless the angle is finite.
  PhasedTrajectory turned(double course) const;

 private:
  // The phase that holds t, or null past the end.
  const Phase* phase_at(double t) const;

  // The phases' NED offsets from start_, turned by turn_ when turned_ (unturned, nothing is
  // recomputed, so that the commands stay bit for bit those of the file).
  Eigen::Vector3d turned_offset(const Eigen::Vector3d& position) const;

  Eigen::Vector3d start_;
  std::vector<Phase> phases_;
  bool turned_ = false;
  Eigen::Matrix3d turn_ = Eigen::Matrix3d::Identity();
};

}  // namespace thetad
