#pragma once

// The offline half of the gain-scheduled LQR (see docs/lqr-scheduled.md): at every point of a grid
// of straight-flight conditions (ground speed, course, climb rate), the Ipopt trim (x*, u*), the
// Jacobian linearization there and one CARE on the 17 states of V_track (Eq. 36) give an
// operating point and a gain K. The table it builds is what LqrScheduledController blends online
// and what lqr_schedule_file.hpp saves and loads.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/linearization.hpp"
#include "core/helicopter/helicopter.hpp"
#include "settings/settings.hpp"

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
  // thrust-inversion model (A4) has no trim (docs/model.md §11 ).
  heli::ModelOptions::RotorSpeedModel rotor_speed_model = heli::ModelOptions::RotorSpeedModel::thrust_inversion;
  double rotor_speed = 0.0;  // Ω_mr at the trim (rad/s)
  double residual = 0.0;     // Trim::residual
  OperatingPoint point;      // x*, u*, V*
  Eigen::MatrixXd K;         // m × design_states
};

struct LqrScheduleTable {
  // The table file's "format_version" (controllers/lqr_schedule_file.hpp, docs/lqr-scheduled.md):
  //   1: the key was "version".
  //   2: "format_version", as every thetad document says it (docs/glossary.md); the table is as in 1.
  static constexpr int kFormatVersion = 2;
  // The gains act on V_track without the bias state s (constant, so no state of the design).
  static constexpr int kDesignStates = heli::kStateDim - 1;

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
// central differences do not straddle the jump (lqr_schedule_design.cpp).
Eigen::VectorXd lqr_linearization_state(const Eigen::VectorXd& trim_state);

// Called after each designed point (progress displays).
using LqrDesignProgress = std::function<void(std::size_t done, std::size_t total, const LqrSchedulePoint& point)>;

// Designs every grid point on `model` (nominal, wind-free: the controller's model). Speeds are
// swept upwards with the previous trim as Ipopt's initial guess. Throws thetad::Error naming the
// point when neither rotor model has a trim there or the CARE has no stabilizing solution.
LqrScheduleTable design_lqr_schedule(const heli::Helicopter& model, const LqrScheduleGrid& grid,
                                     const Eigen::VectorXd& state_weights, const Eigen::VectorXd& input_weights,
                                     const LqrDesignProgress& progress = {});

}  // namespace thetad
