#pragma once

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "core/control_law.hpp"
#include "core/sdc_plant.hpp"
#include "core/sim/plant_simulator.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/run_files.hpp"
#include "experiment/run_controls.hpp"

namespace thetad {

// A controller flown on a plant of the user's (any SdcPlant) with the same controller specs and
// run controls as a scenario's flight: what a user's plant needs to fly θ–D and the SDRE.
struct PlantFlightResult {
  ControllerSpec spec;
  YAML::Node settings;  // resolved: every field of the controller's settings
  sim::SimulationSettings simulation;
  Eigen::VectorXd initial_state;
  sim::PlantRun run;
};

// Flies the controller of `spec`, designed for `plant` at x0 with the plant's design defaults,
// from x0 for `controls.duration` (required) tracking `reference` (a regulator ignores it). The
// disturbance controls do not apply (a plain SdcPlant has none). Errors name the settings file.
PlantFlightResult fly_plant(const SdcPlant& plant, const ControllerSpec& spec, const Eigen::VectorXd& x0,
                            const ReferenceTrajectory& reference, const RunControls& controls);

// Writes <folder>/<label>.csv (t_s, x_0 ..., u_0 ...; unless summary-only) and <folder>/<label>.json
// (format thetad-plant-run-1: the plant's name, the controller and its settings, status, cost,
// settings, the build) as write_run_files commits a scenario's run.
inline constexpr const char* kPlantRunFormat = "thetad-plant-run-1";
RunFiles write_plant_run_files(const PlantFlightResult& result, const std::string& plant,
                               const std::filesystem::path& folder);

}  // namespace thetad
