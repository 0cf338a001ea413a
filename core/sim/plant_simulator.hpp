#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/control_law.hpp"
#include "core/sdc_plant.hpp"
#include "core/sim/simulator.hpp"

namespace thetad::sim {

// A flight of any SdcPlant: what simulate() does for the helicopter, without what only the
// helicopter has (its parameter draws, wind, noise and divergence limits). The controller sees the
// true state.
struct PlantRun {
  RunStatus status = RunStatus::completed;
  std::string reason;     // why the run diverged (with the time); empty when completed
  double end_time = 0.0;
  std::int64_t controller_samples = 0;
  // J = 1/2 sum_k (vᵀ Q v + uᵀ R u) T_c, v = plant.tracking_vector(x, reference), with the plant's
  // design weights (SdcPlant::design_defaults()), by left rectangles at the controller rate.
  double cost = 0.0;
  std::vector<std::pair<std::string, double>> controller_counters;
  // One row per logged controller sample (none when settings.keep_log is false): t, x (n), u (m).
  Eigen::MatrixXd log;
};

// Flies `law` on `plant` from x0 for settings.duration: RK4 steps of settings.dt, the controller
// every settings.controller_period() with zero-order hold, the reference's integral by the
// PositionIntegral rule. A non-finite state or command, |x|_inf > max_state, or a thetad::Error from
// the plant or the controller ends the run as diverged. Throws thetad::Error for invalid settings
// or a wrongly sized x0.
PlantRun simulate_plant(ControlLaw& law, const SdcPlant& plant, const ReferenceTrajectory& reference,
                        const Eigen::VectorXd& x0, const SimulationSettings& settings, double max_state = 1e6);

}  // namespace thetad::sim
