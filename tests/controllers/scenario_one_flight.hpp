#pragma once

// States along scenario I: the samples the simulator handed θ–D (the registry's defaults) in a
// closed-loop run of scenario-1.yaml with all its disturbances, from `from` to `to` seconds.
// For the tests that replay real states to a controller or a solver.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/sim/recording_law.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "scenarios/scenario.hpp"

namespace thetad::testing {

struct ScenarioOneFlight {
  Scenario scenario = load_scenario(THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml");
  heli::Helicopter model{heli::Parameters::nominal(), scenario.model_options};
  std::vector<sim::ControlSample> samples;

  ScenarioOneFlight(double from, double to) {
    sim::SimulationSettings settings = scenario.simulation_settings();
    settings.duration = to;
    settings.measure_compute_time = false;
    settings.keep_log = false;
    const auto theta_d = make("theta-d", YAML::Node());
    sim::RecordingLaw law(*theta_d, from, samples);
    const sim::RunResult run = sim::simulate(law, scenario.trajectory, scenario.initial_state, settings,
                                             heli::Parameters::nominal(), scenario.model_options);
    if (run.summary.status != sim::RunStatus::completed) throw Error("the recording run failed: " + run.summary.reason);
  }

  // A controller by its registered name, as `thetad run` builds it for this scenario.
  std::unique_ptr<Controller> make(const std::string& name, const YAML::Node& settings) const {
    return ControllerRegistry::instance().make(name, settings, ControllerContext{model, scenario.initial_state, 0.0});
  }
};

// 0.2 … 1.2 s, recorded once per test program.
inline const ScenarioOneFlight& scenario_one_flight() {
  static const ScenarioOneFlight flight(0.2, 1.2);
  return flight;
}

}  // namespace thetad::testing
