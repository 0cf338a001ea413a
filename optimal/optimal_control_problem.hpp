#pragma once

#include <memory>
#include <optional>

#include <Eigen/Core>

#include "core/control_law.hpp"
#include "core/feedforward.hpp"
#include "core/sdc_plant.hpp"

namespace thetad {

// A finite-horizon optimal control problem on a plant, priced as a run's cost J is priced:
//
//   min over u   J = 1/2 sum_k (v_kᵀ Q v_k + u_kᵀ R u_k) T_c     (k = 0 .. samples − 1)
//   subject to   the plant's RK4 steps of dt, u held between samples, from initial_state,
//
// with v_k the plant's tracking vector at controller sample k (SdcPlant::tracking_vector, the
// reference's integral by the PositionIntegral rule) and Q, R diagonal: the J of
// sim::RunSummary::cost, sample for sample. With `deviation_trims` the cost is J_dev instead
// (sim::RunSummary::cost_dev, docs/model.md §7.2): v_k − V*_k and u_k − u_r,k are priced, V* and
// u_r the commanded motion and its trim as sim::DeviationCost takes them. The input is further held
// over shooting intervals of `interval_periods` controller periods (the transcription's unknowns),
// within [input_lower, input_upper] when those are given.
struct OptimalControlProblem {
  const SdcPlant* plant = nullptr;
  const ReferenceTrajectory* reference = nullptr;
  Eigen::VectorXd initial_state;
  // The controller sample the horizon starts at, t = first_sample T_c: the reference is read, and
  // its integral accumulated, from t = 0 as in the flight the horizon is a segment of.
  int first_sample = 0;
  Eigen::VectorXd state_weights;  // diagonal of Q (n)
  Eigen::VectorXd input_weights;  // diagonal of R (m)
  // Set: the cost is J_dev on these trims (the plant needs a bias state); unset: J.
  std::shared_ptr<const TrimSource> deviation_trims;
  // Both empty (no bounds) or both m entries, lower ≤ upper: the actuators' magnitude limits.
  Eigen::VectorXd input_lower, input_upper;
  double dt = 1e-3;               // RK4 step (s): the simulator's
  int controller_period_steps = 1;  // T_c = dt * controller_period_steps: where J samples
  int interval_periods = 1;       // controller periods per shooting interval (u held over it)
  int intervals = 1;              // the horizon is intervals * interval_periods * T_c
  // The helicopter's simulate() prices the tracking vector's three integral entries (from this
  // index) with the left-rectangle integral of the position error x[0..2] − reference, not with
  // the plant's own integral states: set it to heli::kXi to price as simulate() does. Unset: the
  // tracking vector of the state itself, as sim::simulate() prices it.
  std::optional<int> sampled_position_integral;
  // That sampled integral at the start of the horizon (0 from the start of a flight).
  Eigen::Vector3d initial_integral = Eigen::Vector3d::Zero();
  // A plant that gives no Jacobian (SdcPlant::jacobian) is differentiated by central differences
  // of f when set (slower, and exact to about eps^(2/3) only), refused when not.
  bool finite_differences = false;

  double controller_period() const { return dt * controller_period_steps; }
  int samples() const { return intervals * interval_periods; }
  double horizon() const { return samples() * controller_period(); }
  double start_time() const { return first_sample * controller_period(); }
  // The entries of a shooting node: the plant state, then the sampled integral (3) when priced.
  int node_dim() const;
  bool bounded() const { return input_lower.size() > 0; }

  // Throws thetad::Error naming the first field that is missing, mis-sized or out of range.
  void validate() const;
};

}  // namespace thetad
