#include "controllers/examples/pid.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "controllers/registry.hpp"
#include "settings/settings.hpp"
#include "core/error.hpp"
#include "core/helicopter/state.hpp"

namespace thetad {

using namespace heli;  // the state and input indices

ExamplePidController::ExamplePidController(const Trim& hover, PidGains gains, double mass, double gravity)
    : hover_state_(hover.state), hover_input_(hover.input), gains_(std::move(gains)), mass_(mass), gravity_(gravity) {}

void ExamplePidController::control(double, const Eigen::Ref<const Eigen::VectorXd>& x,
                                   const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  const double phi = x(kPhi), theta = x(kTheta), psi = x(kPsi);
  // Errors in the heading frame (x forward, y right, z down): NED rotated by −ψ; the body
  // velocity rotated by roll and pitch.
  const Eigen::Matrix3d to_heading = Eigen::AngleAxisd(-psi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d error = to_heading * (x.segment<3>(kXp) - reference.position);
  const Eigen::Vector3d integral = to_heading * (x.segment<3>(kXi) - reference.integral);
  const Eigen::Vector3d velocity = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()) *
                                   (Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitX()) * x.segment<3>(kU));

  // Outer loop: commanded accelerations.
  Eigen::Vector3d acceleration;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d& k = axis < 2 ? gains_.position : gains_.altitude;
    acceleration(axis) = -k(0) * error(axis) - k(1) * integral(axis) - k(2) * velocity(axis);
  }
  const double pitch_command = hover_state_(kTheta) - acceleration.x() / gravity_;
  const double roll_command = hover_state_(kPhi) + acceleration.y() / gravity_;

  // Inner loop around the trim inputs.
  u = hover_input_;
  u(kTmr) -= mass_ * acceleration.z();
  u(kLon) += gains_.pitch(0) * (pitch_command - theta) - gains_.pitch(1) * x(kQ);
  u(kLat) += gains_.roll(0) * (roll_command - phi) - gains_.roll(1) * x(kP);
  // ṙ falls with δ_ped: a positive heading error needs more pedal.
  u(kPed) += gains_.yaw(0) * std::remainder(psi - hover_state_(kPsi), 2.0 * std::numbers::pi) + gains_.yaw(1) * x(kR);
}

namespace {

std::unique_ptr<Controller> make_example_pid(const Settings& fields, const ControllerContext& context) {
  const Helicopter& model = helicopter_of(context, "example-pid");
  fields.allow_only({"position_gains", "altitude_gains", "roll_gains", "pitch_gains", "yaw_gains"});
  PidGains gains;
  gains.position = fields.vector("position_gains", gains.position, 3, 0.0);
  gains.altitude = fields.vector("altitude_gains", gains.altitude, 3, 0.0);
  gains.roll = fields.vector("roll_gains", gains.roll, 2, 0.0);
  gains.pitch = fields.vector("pitch_gains", gains.pitch, 2, 0.0);
  gains.yaw = fields.vector("yaw_gains", gains.yaw, 2, 0.0);
  if (context.settings_only) return nullptr;
  // Hover at the start's altitude and heading: the trim gives the attitude and inputs that hold it.
  const Eigen::VectorXd& x0 = context.initial_state;
  if (x0.size() != kStateDim) throw Error("example-pid: initial state has " + std::to_string(x0.size()) + " entries, not 18");
  const Trim hover = find_trim(model, TrimCondition::hover(-x0(kZp), x0(kPsi)));
  const Parameters& p = model.parameters();
  return std::make_unique<ExamplePidController>(hover, std::move(gains), p.mass, p.gravity);
}

const ControllerRegistration example_pid_registration = register_controller<ExamplePidController>(
    "cascaded PID around the hover trim (the template for your own controller); settings: "
                   "position_gains, altitude_gains ([kp, ki, kd]), roll_gains, pitch_gains, yaw_gains ([k, k_rate])",
    make_example_pid);

}  // namespace

}  // namespace thetad
