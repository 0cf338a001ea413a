#pragma once

// Weights designed for the helicopter, not inherited (docs/weights.md): Bryson's rule on stated
// allowed excursions and input headroom, then checks of every built-in controller's linearized
// closed loop at every trim of an envelope, sampled at 1 kHz and at 100 Hz with a zero-order hold
// and one sample of delay, and a deterministic adjustment per axis until the checks hold. One set
// of Q, R that every controller flies.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/lqr_schedule_design.hpp"
#include "core/helicopter/helicopter.hpp"

namespace thetad {

// What the design is asked for.
struct WeightDesignInputs {
  // Bryson's rule, Q_ii = 1 / x_max², R_jj = 1 / u_max²: the largest deviation of each tracking
  // entry the closed loop may show, by group.
  double position = 0.5;   // m
  double velocity = 1.0;   // m/s, body
  double attitude = 0.15;  // rad, roll and pitch
  double heading = 0.1;    // rad
  double rate = 0.5;       // rad/s
  double flapping = 0.05;  // rad
  double integral = 1.0;   // m s, position-error integrals
  // The input's headroom from hover to the actuator limits (docs/model.md §12), the smaller side
  // of each channel (thrust: ~80 N down, ~133 N up), as the start of R and as the bound of the
  // checks, which allow `headroom_share` of it.
  double headroom_share = 0.8;
  // Where the checks are made: the trims of this grid.
  LqrScheduleGrid envelope = LqrScheduleGrid::envelope();
  // The smallest balanced disk margin every sampled loop must keep (0.3: gain margins 0.74 to
  // 1.35, ±2.6 dB, and ±17° of phase, simultaneously in every input channel).
  double min_disk_margin = 0.3;
  // Controller periods checked (s): 1 kHz and 100 Hz.
  std::vector<double> periods = {1e-3, 1e-2};
  int max_adjustments = 24;
};

// The worst figure of one check over the envelope, and where.
struct WeightCheck {
  std::string controller;  // theta-d, sdre, lqr (the hover gain), lqr-scheduled (the trim's gain)
  double period = 0.0;     // s
  double spectral_radius = 0.0;  // of the sampled loop with delay: < 1 is stable
  double disk_margin = 0.0;      // balanced multiloop disk margin at the plant input (σ̄ bound)
  // Largest |Δu_j| / headroom_j over the responses to 1 m steps in x, y, h and to 1 m/s² of
  // commanded acceleration along x, y, z.
  double peak_input_share = 0.0;
  std::string peak_input;  // "T_mr, step in h at 10 m/s, course 90 deg, climb 0 m/s"
  std::string worst_point; // where the spectral radius is largest
};

struct WeightDesign {
  WeightDesignInputs inputs;
  Eigen::VectorXd headroom;       // per input channel (N, rad)
  Eigen::VectorXd state_weights;  // diagonal of Q (18, the bias state 0)
  Eigen::VectorXd input_weights;  // diagonal of R (5)
  std::vector<WeightCheck> checks;  // of the final weights, per controller and period
  // Envelope points where the model's own rotor-speed model has no trim (only the governor's):
  // no controller of this model flies there, so they are not checked.
  int skipped_points = 0;
  int adjustments = 0;
  bool holds = false;
  std::vector<std::string> unmet;  // what could not be met, when !holds
};

// Designs the weights for `model` (its options: the scenario's). Throws thetad::Error when a trim
// of the envelope cannot be found or a CARE has no stabilizing solution.
WeightDesign design_weights(const heli::Helicopter& model, const WeightDesignInputs& inputs = {});

// The settings file every built-in controller flies (a block per controller with Q and R), its
// design inputs and checks written in it as comments.
std::string weights_settings_text(const WeightDesign& design);

}  // namespace thetad
