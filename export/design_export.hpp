#pragma once

// The per-controller halves of `thetad export` (controller_export.cpp assembles the header): each
// turns a designed controller into its constant data and the typed wrappers of its onboard step.

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controllers/lqr.hpp"
#include "controllers/sdre.hpp"
#include "controllers/theta_d.hpp"
#include "export/constant_source.hpp"

namespace thetad {

struct ExportedDesign {
  DesignSource data;        // the generated `template <class T> struct Design`
  std::vector<std::string> step_files;  // the export/onboard/ files with its step, in include order
  std::string wrappers;     // State<T>, reset(), step(), set_applied_input() over Design<T>
  Eigen::MatrixXd input_weights;  // R, by which the check measures differences of u
  Eigen::VectorXd initial_input;  // what the step applied before its first sample (reset())
  // What the step carries between samples beyond the applied input (the SDRE's P), read from the
  // library's controller after a sample, and the wrapper that sets it from doubles: a check run
  // that starts in the middle of the flight resumes from it. None for θ–D and the LQR.
  std::function<std::vector<double>(const Controller&)> carried_state;
  std::string carried_state_setter;
};

// The wrappers of a step with an input fixed point (export/onboard/step_common.hpp): State<T> as
// `state_type`, reset() (after `reset_comment`), step() and set_applied_input() over thetad_onboard's
// PREFIX_reset and PREFIX_step with Design<T>.
std::string fixed_point_step_wrappers(const std::string& state_type, const std::string& prefix,
                                      const std::string& reset_comment);

// θ–D after reset() (its design: A0, g0, T0, Ac0 at the initial state): the step of
// export/onboard/theta_d_step.hpp; `feedforward_velocity` when it flies the velocity error form.
ExportedDesign theta_d_design(const ThetaDController& controller, bool feedforward_velocity);

// The LQR with feedforward none: export/onboard/lqr_step.hpp with its gain and operating point;
// `input_weights` is the R it was designed with.
ExportedDesign lqr_design(const LqrController& controller, const Eigen::MatrixXd& input_weights);

// The SDRE in mode capped after reset() (its P at the design point): export/onboard/sdre_step.hpp
// with that P, the weights and the fixed-point settings.
ExportedDesign sdre_design(const SdreController& controller);

}  // namespace thetad
