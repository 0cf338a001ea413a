#pragma once

// Gain-scheduled LQR over the flight envelope (see docs/lqr-scheduled.md):
//  - offline (lqr_schedule_design.hpp), at every point of a grid of straight-flight conditions
//    (ground speed, course, climb rate), the Ipopt trim (x*, u*), the Jacobian linearization there
//    and one CARE with the paper's Q and R on the 17 states of V_track (Eq. 36) give an operating
//    point and a gain K;
//  - online (here), the commanded velocity (from the reference) selects the flight condition, the
//    trims and gains of the surrounding grid points are blended multilinearly (clamped at the
//    grid's edges, periodic in course) and u = u* − K (V − V*), V = V_track of the measured state.
// The table (grid, trims, gains) can be built once and saved (`thetad design-lqr`), then loaded by
// the controller (`table: FILE`, lqr_schedule_file.hpp); it records the model it was designed on,
// and a table designed on another model (options or parameters) is rejected.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/controller.hpp"
#include "controllers/lqr_schedule_design.hpp"
#include "controllers/lqr_schedule_file.hpp"
#include "core/helicopter/helicopter.hpp"

namespace thetad {

// One step of the scheduling velocity: `velocity` moves towards the backward difference of the
// reference over `period` through a first-order low pass with `time_constant` (exact for a held
// input; 0: no filter).
void advance_scheduling_velocity(const Eigen::Vector3d& reference_step, double period, double time_constant,
                                 Eigen::Vector3d& velocity);

// Flies the scheduling velocity along `reference` for `duration` at `period`, as the controller
// will, and throws thetad::Error naming the first time and velocity that `grid` does not hold
// (speed beyond its speeds, climb rate beyond its climb rates, a course off its only course):
// there the controller would clamp to the grid's edge and fly trims of another flight.
// With exact_velocity, the reference's own velocity is checked (no filter).
void check_lqr_envelope(const LqrScheduleGrid& grid, double velocity_time_constant, const ReferenceTrajectory& reference,
                        double duration, double period, bool exact_velocity = false);

class LqrScheduledController final : public NamedController<"lqr-scheduled"> {
 public:
  static constexpr int kDesignStates = LqrScheduleTable::kDesignStates;
  using Gain = Eigen::Matrix<double, heli::kInputDim, kDesignStates>;
  using DesignVector = Eigen::Matrix<double, kDesignStates, 1>;
  using Input = Eigen::Matrix<double, heli::kInputDim, 1>;

  // The scheduling velocity is the reference's, low-passed with this time constant (s): the
  // scenarios' commanded velocity jumps at phase boundaries (docs/model.md §10), and a jump of V*'s
  // velocity by 0.5 m/s in w at the end of the takeoff ramp commands −36 N of thrust through the
  // w gain (~230 N per m/s), which A4 has no rotor speed for. Longer is gentler and lags more:
  // 0.2 s keeps the smallest thrust of the paper runs above 17 N (10 N at 0.1 s) for ~13 % more
  // tracking error than 0.1 s (docs/lqr-scheduled.md).
  static constexpr double kDefaultVelocityTimeConstant = 0.2;

  // Keeps a reference to the model (it must outlive the controller and its clones); clones share
  // the table. Throws thetad::Error when the table's sizes do not fit the helicopter or the time
  // constant is negative.
  //
  // feedforward (docs/model.md §7.1): velocity+trim (the default) schedules the gain and the trim
  // V*, u* on the commanded velocity; velocity flies the table's hover point with V*'s body
  // velocity the commanded one (in the hover trim's attitude frame); none flies the hover point
  // alone, the hover LQR of this table. exact_velocity: the commanded velocity is the reference's
  // exact one, not the low-passed backward difference of its position.
  LqrScheduledController(const heli::Helicopter& model, std::shared_ptr<const LqrScheduleTable> table,
                         double velocity_time_constant = kDefaultVelocityTimeConstant,
                         FeedForward feedforward = FeedForward::velocity_trim, bool exact_velocity = false);

  std::unique_ptr<Controller> clone() const override { return std::make_unique<LqrScheduledController>(*this); }

  void reset(const Eigen::VectorXd& x0, double t0) override;
  // Schedules on the commanded velocity (backward difference of the reference between samples,
  // low-passed), then u = u* − K (V − V*). Allocates nothing.
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override;

  // Blends the grid's trims and gains at a flight condition; the results are read back with
  // gain(), trim_input() and trim_tracking(). Allocates nothing.
  void schedule(double speed, double course, double climb_rate);
  const Gain& gain() const { return gain_; }
  const Input& trim_input() const { return trim_input_; }
  const DesignVector& trim_tracking() const { return trim_tracking_; }
  FeedForward feedforward() const { return feedforward_; }
  // The (low-passed) commanded NED velocity the last control step scheduled on.
  const Eigen::Vector3d& scheduled_velocity() const { return velocity_; }
  const LqrScheduleTable& table() const { return *table_; }

 private:
  // V*'s body velocities: the NED velocity seen from the blended trim attitude.
  void set_trim_body_velocity(const Eigen::Vector3d& velocity_ned);

  const heli::Helicopter* model_;
  std::shared_ptr<const LqrScheduleTable> table_;
  double velocity_time_constant_;
  FeedForward feedforward_;
  bool exact_velocity_;
  // The table's points in fixed-size form, in the table's order (the hot path reads only these).
  std::vector<Gain> gains_;
  std::vector<DesignVector> tracking_;
  std::vector<Input> inputs_;

  Gain gain_;
  Input trim_input_;
  DesignVector trim_tracking_;
  Eigen::VectorXd v_;  // V_track of the measured state
  Eigen::Vector3d previous_reference_ = Eigen::Vector3d::Zero();
  double previous_time_ = 0.0;
  bool has_previous_ = false;
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();
};

}  // namespace thetad
