#pragma once

// Gain-scheduled LQR over the flight envelope (see docs/lqr-scheduled.md):
//  - offline, at every point of a grid of straight-flight conditions (ground speed, course, climb
//    rate), the Ipopt trim (x*, u*), the Jacobian linearization there and one CARE with the paper's
//    Q and R on the 17 states of V_track (Eq. 36) give an operating point and a gain K;
//  - online, the commanded velocity (from the reference) selects the flight condition, the trims
//    and gains of the surrounding grid points are blended multilinearly (clamped at the grid's
//    edges, periodic in course) and u = u* − K (V − V*), V = V_track of the measured state.
// The table (grid, trims, gains) can be built once and saved (`thetad design-lqr`), then loaded by
// the controller (`table: FILE`); it records the model it was designed on, and a table designed on
// another model (options or parameters) is rejected.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "controllers/controller.hpp"
#include "controllers/linearization.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/settings.hpp"

namespace thetad {

// The flight conditions of a schedule. Trims are flown at heading 0 (the paper holds ψ = 0), so a
// course is the direction of flight relative to the nose: 0 forward, π/2 to the right, π rearward.
struct LqrScheduleGrid {
  std::vector<double> speeds;       // horizontal ground speed (m/s), strictly ascending, >= 0
  std::vector<double> courses;      // rad, strictly ascending in [0, 2π); periodic when > 1
  std::vector<double> climb_rates;  // m/s (up positive), strictly ascending
  // The trims' altitude (m). The model has no altitude dependence (constant air density), so it
  // only places x*; position errors are taken from the reference, not from x*.
  double altitude = 3.5;

  // The default envelope: 0…20 m/s, 8 courses, climb −1…1 m/s (docs/lqr-scheduled.md).
  static LqrScheduleGrid envelope();
  // One point, hover: the scheduled controller is then the hover LQR.
  static LqrScheduleGrid hover();

  std::size_t size() const { return speeds.size() * courses.size() * climb_rates.size(); }
  // Throws thetad::Error naming the first list that is empty, unsorted or out of range.
  void validate() const;
};

// A grid from a settings block (a YAML or JSON map): speeds (m/s), courses_deg, climb_rates (m/s),
// altitude (m); a missing key keeps the envelope's value. Every field is recorded in the block's
// resolved(), as given. Errors are SettingsErrors naming the field.
LqrScheduleGrid read_lqr_grid(const Settings& fields);

// One designed grid point.
struct LqrSchedulePoint {
  double speed = 0.0, course = 0.0, climb_rate = 0.0;
  // The rotor model the trim and linearization used: the model's own, or the governor where the
  // thrust-inversion model (A4) has no trim (spec A-11).
  heli::ModelOptions::RotorSpeedModel rotor_speed_model = heli::ModelOptions::RotorSpeedModel::thrust_inversion;
  double rotor_speed = 0.0;  // Ω_mr at the trim (rad/s)
  double residual = 0.0;     // Trim::residual
  OperatingPoint point;      // x*, u*, V*
  Eigen::MatrixXd K;         // m × design_states
};

struct LqrScheduleTable {
  static constexpr int kFormatVersion = 1;

  LqrScheduleGrid grid;
  Eigen::VectorXd state_weights;  // diagonal of Q (n entries; only design_states are used)
  Eigen::VectorXd input_weights;  // diagonal of R
  Eigen::Index design_states = 0;
  std::string model_options;  // heli::ModelOptions::to_string() of the design model
  std::uint64_t model_hash = 0;
  // Point (speed i, course j, climb k) at index (i · courses + j) · climb_rates + k.
  std::vector<LqrSchedulePoint> points;

  std::size_t index(std::size_t speed, std::size_t course, std::size_t climb) const {
    return (speed * grid.courses.size() + course) * grid.climb_rates.size() + climb;
  }
};

// A fingerprint of the model's options and parameters (FNV-1a over both): a table designed on a
// different model has different trims and gains.
std::uint64_t model_hash(const heli::Helicopter& model);

// Where a trim's Jacobians are taken: the trim state, except in sideways flight (u_a = 0, v_a ≠ 0),
// where u is moved 1e-4 m/s onto the model's u_a >= 0 branch of the jump of sign(u_a), so that
// central differences do not straddle the jump (lqr_scheduled.cpp).
Eigen::VectorXd lqr_linearization_state(const Eigen::VectorXd& trim_state);

// Called after each designed point (progress displays).
using LqrDesignProgress = std::function<void(std::size_t done, std::size_t total, const LqrSchedulePoint& point)>;

// Designs every grid point on `model` (nominal, wind-free: the controller's model). Speeds are
// swept upwards with the previous trim as Ipopt's initial guess. Throws thetad::Error naming the
// point when neither rotor model has a trim there or the CARE has no stabilizing solution.
LqrScheduleTable design_lqr_schedule(const heli::Helicopter& model, const LqrScheduleGrid& grid,
                                     const Eigen::VectorXd& state_weights, const Eigen::VectorXd& input_weights,
                                     const LqrDesignProgress& progress = {});

// JSON (docs/lqr-scheduled.md). Errors name the file, the field and the reason.
void save_lqr_schedule(const LqrScheduleTable& table, const std::filesystem::path& file);
LqrScheduleTable load_lqr_schedule(const std::filesystem::path& file);
// Throws thetad::Error when `table` was designed on another model than `model` (`source` names it).
void check_lqr_schedule_model(const LqrScheduleTable& table, const heli::Helicopter& model, const std::string& source);

class LqrScheduledController final : public Controller {
 public:
  static constexpr int kDesignStates = heli::kStateDim - 1;  // V_track without s
  using Gain = Eigen::Matrix<double, heli::kInputDim, kDesignStates>;
  using DesignVector = Eigen::Matrix<double, kDesignStates, 1>;
  using Input = Eigen::Matrix<double, heli::kInputDim, 1>;

  // The scheduling velocity is the reference's, low-passed with this time constant (s): the
  // scenarios' commanded velocity jumps at phase boundaries (spec §8.4), and a jump of V*'s
  // velocity by 0.5 m/s in w at the end of the takeoff ramp commands −36 N of thrust through the
  // w gain (~230 N per m/s), which A4 has no rotor speed for. Longer is gentler and lags more:
  // 0.2 s keeps the smallest thrust of the paper runs above 17 N (10 N at 0.1 s) for ~13 % more
  // tracking error than 0.1 s (docs/lqr-scheduled.md).
  static constexpr double kDefaultVelocityTimeConstant = 0.2;

  // Keeps a reference to the model (it must outlive the controller and its clones); clones share
  // the table. Throws thetad::Error when the table's sizes do not fit the helicopter or the time
  // constant is negative.
  LqrScheduledController(const heli::Helicopter& model, std::shared_ptr<const LqrScheduleTable> table,
                         double velocity_time_constant = kDefaultVelocityTimeConstant);

  std::string name() const override { return "lqr-scheduled"; }
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
  // The (low-passed) commanded NED velocity the last control step scheduled on.
  const Eigen::Vector3d& scheduled_velocity() const { return velocity_; }
  const LqrScheduleTable& table() const { return *table_; }

 private:
  const heli::Helicopter* model_;
  std::shared_ptr<const LqrScheduleTable> table_;
  double velocity_time_constant_;
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
