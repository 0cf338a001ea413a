#pragma once

#include <filesystem>
#include <string>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "core/helicopter/model_options.hpp"
#include "core/sim/simulation_settings.hpp"
#include "scenarios/trajectory.hpp"
#include "settings/run_controls.hpp"

namespace thetad {

// What to fly (docs/scenarios.md describes the file format): a commanded trajectory made of
// phases, the initial state, and the simulation settings the scenario needs. Everything not set
// by the file keeps thetad's defaults: the paper's disturbances, the X-Cell's actuator limits
// (sim::SimulationSettings{}), the resolved model preset. The paper-literal preset flies without
// actuator limits unless the file asks for them.
//
// A file may name a registered plant instead (`plant: tora`, docs/plants.md): it then says the
// plant's settings, its initial state and the duration, and the flight regulates it to the origin
// with neither disturbances nor actuator limits; what only the helicopter has is refused by name.
struct Scenario {
  std::string name;
  std::string description;
  std::string source;  // the file it was read from ("" when parsed from text)
  double duration = 0.0;  // s; equals the end of the last phase
  // The plant registry's name of the plant flown (experiment/plant_registry.hpp); empty: the helicopter.
  std::string plant;
  YAML::Node plant_settings;  // the plant's settings block (undefined: its defaults)
  // The 18-state xa(t0); by default at rest on the ground, level, s = 1 (docs/model.md §8.1). For
  // a plant, its initial state as the file gives it; empty: the plant's own.
  Eigen::VectorXd initial_state;
  PhasedTrajectory trajectory;
  heli::ModelOptions model_options;
  std::string model_preset = "resolved";  // the preset model_options started from

  // What the file's `simulation:` says about the flight, as run controls (read row by row by the
  // run settings' table, settings/run_settings.hpp); unset keeps the base value. Its duration
  // (simulation.duration) flies less (or, holding the last phase's end, more) than the phases'.
  // The actuator limits default to the base's, and to off with the paper-literal preset.
  RunControls simulation;

  // This scenario with its trajectory flown `speed_scale` times faster (PhasedTrajectory::time_scaled):
  // the same path in 1/s of the time, so duration and simulation.duration shrink by s too, and a
  // flight still covers the whole path, hovers included. What is physics rather than task keeps
  // its time: the plant and controller steps, the wind (its onset too) and the noises. Throws
  // thetad::Error unless s is positive and finite.
  Scenario at_speed(double speed_scale) const;
  // This scenario with its trajectory turned by `course` (rad, north towards east) about its start
  // (PhasedTrajectory::turned): a leg written northwards flown on any course, the initial state
  // (heading included) as written. Throws thetad::Error unless the angle is finite.
  Scenario turned(double course) const;

  // `base` (default: SimulationSettings's defaults) with this scenario's duration and overrides
  // applied. Two overloads, not a default argument: GCC 12 warns falsely (-Wmaybe-uninitialized)
  // on the strings of a defaulted temporary's destruction where the caller inlines it.
  sim::SimulationSettings simulation_settings() const;
  sim::SimulationSettings simulation_settings(sim::SimulationSettings base) const;
};

// `scenario` as the controls fly it: at controls.speed_scale, turned by controls.course (itself
// without either).
Scenario as_flown(const RunControls& controls, const Scenario& scenario);

// Reads a scenario file. Every problem throws thetad::Error with one line that names the file,
// the 1-based line and column, the field and the reason
// ("scenarios/scenario-1.yaml:14:7: field 'phases.figure8.period': must be > 0"); a file that
// cannot be read names the file and the system's reason.
Scenario load_scenario(const std::filesystem::path& file);

// The same from text; `source` names it in messages and Scenario::source.
Scenario parse_scenario(const std::string& text, const std::string& source);

}  // namespace thetad
