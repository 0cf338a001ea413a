#include "controllers/lqr_scheduled.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>

#include "controllers/feedforward_controller.hpp"
#include "controllers/registry.hpp"
#include "core/grid_bracket.hpp"
#include "core/error.hpp"
#include "settings/settings.hpp"

namespace thetad {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

}  // namespace

LqrScheduledController::LqrScheduledController(const heli::Helicopter& model,
                                               std::shared_ptr<const LqrScheduleTable> table,
                                               double velocity_time_constant, FeedForward feedforward,
                                               bool exact_velocity)
    : model_(&model),
      table_(std::move(table)),
      velocity_time_constant_(velocity_time_constant),
      feedforward_(feedforward),
      exact_velocity_(exact_velocity),
      v_(Eigen::VectorXd::Zero(heli::kStateDim)) {
  if (!(velocity_time_constant_ >= 0.0) || !std::isfinite(velocity_time_constant_)) {
    throw Error("lqr-scheduled: the velocity time constant must be finite and >= 0");
  }
  if (!table_ || table_->points.empty() || table_->points.size() != table_->grid.size()) {
    throw Error("lqr-scheduled: the table has no points or not one per grid point");
  }
  gains_.reserve(table_->points.size());
  tracking_.reserve(table_->points.size());
  inputs_.reserve(table_->points.size());
  for (const LqrSchedulePoint& point : table_->points) {
    if (point.K.rows() != heli::kInputDim || point.K.cols() != kDesignStates ||
        point.point.tracking.size() != heli::kStateDim || point.point.input.size() != heli::kInputDim) {
      throw Error("lqr-scheduled: a table point's gain, tracking vector or input does not fit the helicopter");
    }
    gains_.push_back(point.K);
    tracking_.push_back(point.point.tracking.head<kDesignStates>());
    inputs_.push_back(point.point.input);
  }
  schedule(0.0, 0.0, 0.0);
}

void LqrScheduledController::reset(const Eigen::VectorXd& x0, double) {
  if (x0.size() != heli::kStateDim) {
    throw Error("lqr-scheduled: initial state has " + std::to_string(x0.size()) + " entries, the model " +
                std::to_string(heli::kStateDim));
  }
  has_previous_ = false;
  velocity_.setZero();
}

void LqrScheduledController::schedule(double speed, double course, double climb_rate) {
  const LqrScheduleGrid& grid = table_->grid;
  const GridBracket s = bracket(grid.speeds, speed);
  const GridBracket c = periodic_bracket(grid.courses, course);
  const GridBracket h = bracket(grid.climb_rates, climb_rate);
  gain_.setZero();
  trim_input_.setZero();
  trim_tracking_.setZero();
  for_each_corner(s, c, h, [&](std::size_t i, std::size_t j, std::size_t k, double weight) {
    const std::size_t index = table_->index(i, j, k);
    gain_.noalias() += weight * gains_[index];
    trim_input_.noalias() += weight * inputs_[index];
    trim_tracking_.noalias() += weight * tracking_[index];
  });
  // The body velocities of V* are not blended: they are the commanded velocity (clamped to the
  // grid as the trims are) seen from the blended attitude, as at every trim (body = Rᵀ V_ned).
  // Blended linearly in course, the velocity would shrink between courses: at 45° between the 0°
  // and 90° trims, 0.5 of the speed along each body axis instead of 0.71, a velocity error that
  // the gain fights and that costs decimetres of tracking at 3 m/s.
  const double s_value = std::clamp(speed, grid.speeds.front(), grid.speeds.back());
  const double c_value = grid.courses.size() > 1 ? course : grid.courses.front();
  const Eigen::Vector3d velocity_ned(s_value * std::cos(c_value), s_value * std::sin(c_value),
                                     -std::clamp(climb_rate, grid.climb_rates.front(), grid.climb_rates.back()));
  set_trim_body_velocity(velocity_ned);
}

void LqrScheduledController::set_trim_body_velocity(const Eigen::Vector3d& velocity_ned) {
  const Eigen::Matrix3d body_to_ned =
      (Eigen::AngleAxisd(trim_tracking_(heli::kTheta), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(trim_tracking_(heli::kPhi), Eigen::Vector3d::UnitX()))
          .toRotationMatrix();  // R(φ*, θ*, ψ = 0) of Eq. 2
  trim_tracking_.segment<3>(heli::kU).noalias() = body_to_ned.transpose() * velocity_ned;
}

void LqrScheduledController::control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                                     const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  // The commanded velocity: backward difference of the (noise-free) reference over the controller
  // period, through a first-order low pass (exact for a held input); zero at the first sample (the
  // scenarios start at rest). Not the measured velocity: V*'s velocity would then follow the
  // measurement and the velocity error, the damping of the loop, would vanish.
  if (exact_velocity_) {
    velocity_ = reference.velocity;
  } else if (has_previous_ && t > previous_time_) {
    advance_scheduling_velocity(reference.position - previous_reference_, t - previous_time_, velocity_time_constant_,
                                velocity_);
  }
  previous_reference_ = reference.position;
  previous_time_ = t;
  has_previous_ = true;
  // Trims are at heading 0 = the paper's commanded heading: the heading frame is the NED frame.
  if (feedforward_ == FeedForward::velocity_trim) {
    schedule(std::hypot(velocity_.x(), velocity_.y()), std::atan2(velocity_.y(), velocity_.x()), -velocity_.z());
  } else {
    schedule(0.0, 0.0, 0.0);
    if (feedforward_ == FeedForward::velocity) set_trim_body_velocity(velocity_);
  }

  model_->tracking_vector(measured_state, reference, v_);
  const DesignVector error = v_.head<kDesignStates>() - trim_tracking_;
  u = trim_input_;
  u.noalias() -= gain_ * error;
}

void advance_scheduling_velocity(const Eigen::Vector3d& reference_step, double period, double time_constant,
                                 Eigen::Vector3d& velocity) {
  const double blend = time_constant > 0.0 ? 1.0 - std::exp(-period / time_constant) : 1.0;
  velocity += blend * (reference_step / period - velocity);
}

void check_lqr_envelope(const LqrScheduleGrid& grid, double velocity_time_constant, const ReferenceTrajectory& reference,
                        double duration, double period, bool exact_velocity) {
  constexpr double kSlack = 1e-9;  // m/s, rad: rounding of the backward differences
  const auto where = [](double t, const Eigen::Vector3d& v) {
    char text[160];
    std::snprintf(text, sizeof text, "the scenario commands (V_N, V_E, climb) = (%.3g, %.3g, %.3g) m/s at t = %.3f s",
                  v.x(), v.y(), -v.z(), t);
    return std::string(text);
  };
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), previous = reference.position(0.0);
  const auto samples = static_cast<long long>(std::llround(duration / period));
  for (long long k = 1; k < samples; ++k) {
    const double t = static_cast<double>(k) * period;
    const Eigen::Vector3d position = reference.position(t);
    if (exact_velocity) velocity = reference.velocity(t);
    else advance_scheduling_velocity(position - previous, period, velocity_time_constant, velocity);
    previous = position;
    const double speed = std::hypot(velocity.x(), velocity.y()), climb = -velocity.z();
    std::string problem;
    if (speed > grid.speeds.back() + kSlack || speed < grid.speeds.front() - kSlack) {
      problem = "a horizontal speed outside the grid's speeds [" + std::to_string(grid.speeds.front()) + ", " +
                std::to_string(grid.speeds.back()) + "] m/s";
    } else if (climb > grid.climb_rates.back() + kSlack || climb < grid.climb_rates.front() - kSlack) {
      problem = "a climb rate outside the grid's climb rates [" + std::to_string(grid.climb_rates.front()) + ", " +
                std::to_string(grid.climb_rates.back()) + "] m/s";
    } else if (grid.courses.size() == 1 && speed > kSlack) {
      const double off = std::remainder(std::atan2(velocity.y(), velocity.x()) - grid.courses.front(), kTwoPi);
      if (std::abs(off) > 1e-6) problem = "a course off the grid's only course";
    }
    if (!problem.empty()) {
      const std::string source = exact_velocity ? "the reference's exact velocity"
                                                : "the reference's velocity low-passed with " +
                                                      std::to_string(velocity_time_constant) + " s";
      throw Error("lqr-scheduled: " + where(t, velocity) + " (" + source + ", as the controller schedules on it), " +
                  problem +
                  ": beyond it the controller would fly the trims and gains of another flight. Give a grid that "
                  "holds it (settings grid: speeds, courses_deg, climb_rates) or a longer velocity_time_constant");
    }
  }
}

namespace {

std::unique_ptr<Controller> make_lqr_scheduled(const Settings& fields, const ControllerContext& context) {
  const heli::Helicopter& model = helicopter_of(context, "lqr-scheduled");
  fields.allow_only({"table", "grid", "Q", "R", "velocity_time_constant", "velocity_source", "feedforward"});
  const double time_constant = fields.number("velocity_time_constant",
                                             LqrScheduledController::kDefaultVelocityTimeConstant, 0.0, 60.0);
  const bool exact = fields.choice("velocity_source", "filtered", {"filtered", "exact"}) == "exact";
  const FeedForward feedforward = read_feedforward(fields, FeedForward::velocity_trim);
  // Only velocity+trim schedules on the command: the other two fly the table's hover point.
  const bool scheduled = feedforward == FeedForward::velocity_trim && context.reference;
  std::shared_ptr<LqrScheduleTable> table;
  if (fields.has("table")) {
    for (const char* designed : {"grid", "Q", "R"}) {
      if (fields.has(designed)) {
        throw fields.error(designed, "the table fixes the grid and the weights; give either a table or these");
      }
    }
    const std::string file = fields.string("table", "");
    table = std::make_shared<LqrScheduleTable>(load_lqr_schedule(file));
    check_lqr_schedule_model(*table, model, file);
    if (scheduled)
      check_lqr_envelope(table->grid, time_constant, *context.reference, context.duration, context.controller_period,
                         exact);
  } else {
    const LqrScheduleGrid grid = read_lqr_grid(fields.block("grid"));
    // Before the design: a grid that cannot hold the flight fails now, not after seconds of trims.
    if (scheduled)
      check_lqr_envelope(grid, time_constant, *context.reference, context.duration, context.controller_period, exact);
    const Eigen::VectorXd q =
        fields.diagonal_weight("Q", context.defaults.state_weights, Settings::Weight::positive_semidefinite).diagonal();
    const Eigen::VectorXd r =
        fields.diagonal_weight("R", context.defaults.input_weights, Settings::Weight::positive_definite).diagonal();
    if (context.settings_only) return nullptr;
    table = std::make_shared<LqrScheduleTable>(design_lqr_schedule(model, grid, q, r));
  }
  return std::make_unique<LqrScheduledController>(model, std::move(table), time_constant, feedforward, exact);
}

const ControllerRegistration lqr_scheduled_registration = register_controller<LqrScheduledController>(
    "LQR gain-scheduled over trims 0-20 m/s (course, climb), blended on the commanded velocity; settings: "
    "table (a `thetad design-lqr` file) or grid, Q, R; velocity_time_constant, velocity_source (filtered|exact), "
    "feedforward (velocity+trim|velocity|none)",
    make_lqr_scheduled);

}  // namespace

}  // namespace thetad
