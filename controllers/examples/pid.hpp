#pragma once

// A user's own controller, as a template: a cascaded PID for the helicopter that holds a position.
// It is one file pair and one registration (see pid.cpp and docs/api.md, "Plugging in your
// controller"); nothing else in thetad knows about it.
//
// Outer loop (per axis of the heading frame, NED): a commanded acceleration from the position
// error, its integral (the measured state carries it: V_track's integral entries) and the
// velocity. Horizontal accelerations become pitch and roll commands around the hover trim
// (a ≈ −g θ forward, a ≈ g φ right), the vertical one a thrust change −m a_z. Inner loop: P(D) of
// roll, pitch and heading onto the cyclics and the pedal, around their trim values.
//
// Why these gains (X-Cell hover derivatives, docs/model.md §13): a cyclic tilts the rotor through the
// flapping, ḃ1 = −p − 10 b1 + 44.5 δ_lat, ṗ = 300 b1 (pitch: 44.5 and 159), so the rotor itself
// damps the rates (ṗ ≈ −30 p): roll is s³ + 10 s² + 300 s + 13350 k_φ, and k_φ = 0.08 puts its
// slow pole at −3.9 (pitch, k_θ = 0.05: −2.5) with the flapping pair at −3 ± 16j; no rate gain
// is needed. The position loop must stay slower than that (−0.8 ± 0.6j, integral −0.05); altitude acts
// on thrust directly, (s + 2)³. The integral gains are small: the integral error of V_track starts
// at 0 and must return to 0 in an ideal run, so every integral action overshoots (here by < 0.1 m
// from a 1 m offset); it is there for model error and wind.

#include <memory>
#include <string>

#include <Eigen/Core>

#include "controllers/controller.hpp"
#include "core/trim.hpp"

namespace thetad {

struct PidGains {
  Eigen::Vector3d position{1.0, 0.05, 1.6};  // horizontal kp (1/s²), ki (1/s³), kd (1/s)
  Eigen::Vector3d altitude{12.0, 8.0, 6.0};  // vertical kp, ki, kd: (s + 2)³
  Eigen::Vector2d roll{0.08, 0.0};           // δ_lat per rad of roll error, per rad/s of p
  Eigen::Vector2d pitch{0.05, 0.0};          // δ_lon per rad of pitch error, per rad/s of q
  Eigen::Vector2d yaw{0.073, 0.029};         // δ_ped per rad of heading error, per rad/s of r: ṙ ≈ −218 δ_ped
};

// Built into thetad as "example-pid"; its plug-in build (controllers/examples/pid-plugin) is named
// otherwise, since the program it is loaded into has the built-in one already.
#ifndef THETAD_EXAMPLE_PID_NAME
#define THETAD_EXAMPLE_PID_NAME "example-pid"
#endif

// The name is written once, here: register_controller<ExamplePidController> (pid.cpp) takes it.
class ExamplePidController final : public NamedController<THETAD_EXAMPLE_PID_NAME> {
 public:
  // Flies around `hover` (its attitude and inputs are the feed-forward); mass and gravity turn
  // the vertical acceleration command into thrust.
  ExamplePidController(const Trim& hover, PidGains gains, double mass, double gravity);

  std::unique_ptr<Controller> clone() const override { return std::make_unique<ExamplePidController>(*this); }
  void reset(const Eigen::VectorXd&, double) override {}  // no state of its own
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state, const Reference& reference,
               Eigen::Ref<Eigen::VectorXd> u) override;

 private:
  Eigen::Matrix<double, 18, 1> hover_state_;
  Eigen::Matrix<double, 5, 1> hover_input_;
  PidGains gains_;
  double mass_;
  double gravity_;
};

}  // namespace thetad
