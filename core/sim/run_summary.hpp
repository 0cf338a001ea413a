#pragma once

#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/controller_column.hpp"
#include "core/log_column.hpp"
#include "core/sdc_plant.hpp"
#include "core/sim/flight_computer.hpp"
#include "core/sim/saturation_counts.hpp"
#include "core/sim/simulation_settings.hpp"

namespace thetad::sim {

// diverged: the state left the plant's limits or the plant failed; failed: the controller threw
// or returned a non-finite command (a fault of the controller, not of the closed loop).
enum class RunStatus { completed, diverged, failed };

// "completed", "diverged" or "failed", as result files write it.
const char* status_name(RunStatus status);

// "SOURCE failed at t = T s: WHAT": the reason a run ends when the controller or the plant throws.
std::string failure_reason(const char* source, const std::exception& error, double t);

// What a run did, shaped by its plant: one entry per tracked state and per input.
struct RunSummary {
  std::string controller;
  SimulationSettings settings;
  RunStatus status = RunStatus::completed;
  std::string reason;     // why the run diverged or failed (with the time); empty when completed
  double end_time = 0.0;  // duration when completed, else the time it diverged or failed (s)
  std::string model_options;  // the plant's model switches (heli::ModelOptions::to_string()); empty for others
  // The plant's drawn parameter factors p_true / p_nom of this run, in the plant's order (the
  // helicopter: Table 1); empty when nothing was drawn.
  std::vector<std::pair<std::string, double>> parameter_factors;
  std::int64_t controller_samples = 0;  // samples whose control was computed
  // The controller's own event counts at the end of the run (ControlLaw::counters()).
  std::vector<std::pair<std::string, double>> controller_counters;
  // The worst value of each of the controller's certificates over the controller samples and its
  // time (ControlLaw::log_columns, docs/model.md §8.4); empty when it reports none.
  std::vector<CertificateWorst> certificates;
  // The plant's tracked states (SdcPlant::tracked_states) and inputs, naming the vectors below.
  std::vector<TrackedState> tracked;
  std::vector<LogColumn> inputs;
  // True tracked state minus its command over the controller samples, per tracked state.
  Eigen::VectorXd rms_tracking_error;
  Eigen::VectorXd max_tracking_error;
  // Control effort: RMS of the commanded input per channel over the controller samples.
  // Commanded, not applied: it measures the controller, not the noise.
  Eigen::VectorXd command_rms;
  // Controller samples whose applied input the actuator limits changed, per channel.
  SaturationCounts saturation;
  // What the flight computer did, when it was in the loop (settings.computer.active()).
  std::optional<ComputerCounts> computer;
  // J = 1/2 sum_k (vᵀ Q v + uᵀ R u) T_c with the plant's design Q and R, v the tracking vector on
  // the true state (SdcPlant::true_tracking_vector; the helicopter's V_track of Eq. 36, Eq. 32)
  // and u the commanded input, by left rectangles at the controller rate.
  double cost = 0.0;
  // J_dev (sim::DeviationCost, docs/model.md §7.2) and what its weights are; none for a plant
  // without trims or a reference beyond them, and then the weights' text says why ("none: ...").
  std::optional<double> cost_dev;
  std::string cost_dev_weights;
  // Wall time of the control() call per sample (ns); 0 when not measured.
  double compute_ns_mean = 0.0;
  double compute_ns_median = 0.0;
  double compute_ns_p99 = 0.0;
};

}  // namespace thetad::sim
