#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "controllers/controller.hpp"
#include "controllers/registry.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/progress.hpp"
#include "experiment/provenance.hpp"
#include "settings/run_controls.hpp"
#include "experiment/run_result.hpp"
#include "scenarios/scenario.hpp"

namespace thetad {

// A controller built for a flight, with every setting as it was used.
struct PreparedController {
  ControllerSpec spec;
  std::unique_ptr<Controller> controller;
  YAML::Node settings;
  // Where the controller comes from, for a controller the registry does not build (a Python
  // class); empty: the registry's record of spec.controller ("built-in", a plug-in).
  std::string origin;
};

// A plant, what it is asked to fly and the controllers' model of it, ready to fly: the one place
// where a scenario or a plant, run controls and controller specs become results, for every front
// end. Everything that can be wrong with the files is found while building it and preparing the
// controllers, before anything flies or is written.
class Flight {
 public:
  // The flight `scenario` says: a file, or the name of a shipped scenario (find_scenario). The
  // helicopter with the paper's disturbances (sim::HelicopterDisturbances) as the scenario and
  // controls set them; or the registered plant the file names (`plant:`), as of_plant flies it.
  explicit Flight(const std::string& scenario, const RunControls& controls = {});
  // The same from a scenario's text, as a result recorded it; `file` names it in messages.
  static Flight from_text(const std::string& text, const std::string& file, const RunControls& controls);
  // `plant` (named `name` in results) as it is (sim::NoDisturbances), from `initial_state`,
  // regulated to the origin for controls.duration (required). Throws thetad::Error naming what is
  // wrong, controls.plant_settings among it (they set a registered plant's, below).
  static Flight of_plant(std::shared_ptr<const SdcPlant> plant, const std::string& name,
                         const Eigen::VectorXd& initial_state, const RunControls& controls);
  // The same for the plant `name` of the registry (PlantRegistry), built with controls.plant_settings,
  // from its own initial state unless `initial_state` is given.
  static Flight of_plant(const std::string& name, const std::optional<Eigen::VectorXd>& initial_state,
                         const RunControls& controls);

  // The front ends' choice: the flight of `scenario` (a file or a shipped name), or of the
  // registered plant `plant` (from `initial_state` when given); exactly one of the two names.
  static Flight of_scenario_or_plant(const std::string& scenario, const std::string& plant,
                                     const std::optional<Eigen::VectorXd>& initial_state, const RunControls& controls);

  // The scenario as flown: at the controls' speed_scale and course (a plant's flight: named after the plant,
  // holding the origin).
  const Scenario& scenario() const { return scenario_; }
  // Where the plant starts: the scenario's initial state, moved and turned by the controls'
  // initial offsets.
  const Eigen::VectorXd& initial_state() const { return initial_state_; }
  const sim::SimulationSettings& settings() const { return settings_; }
  // The settings a run of the controller labelled `label` flies: settings() with the flight
  // computer's step time of that controller when its latency is the step time (docs/model.md §15.7).
  // Throws thetad::Error when the step times have none for it.
  sim::SimulationSettings flown_settings(const std::string& label) const;
  // The controllers' model: for the helicopter its nominal parameters, the scenario's model
  // options, no wind.
  const SdcPlant& plant() const { return *plant_; }
  // The same as the helicopter; throws thetad::Error naming the plant when the flight has another.
  const heli::Helicopter& model() const;
  // The helicopter, or null when the flight has another plant.
  const heli::Helicopter* helicopter() const { return helicopter_; }
  // What produced a run of this flight, less the controller (and the host and time, stamped per run).
  const Provenance& provenance() const { return provenance_; }
  // "ideal (...)" with neither disturbances nor actuator limits; else "all disturbances (the
  // paper's)", "no uncertainty, noise or wind" or the switches, then whether the limits are on.
  std::string disturbances() const;
  // The disturbances of one run of this flight at its present settings.
  std::unique_ptr<sim::Disturbances> make_disturbances() const;

  // Flies the next runs with `seed` (a campaign's draws reuse one Flight and its controllers).
  void set_seed(std::uint64_t seed) { settings_.seed = provenance_.seed = seed; }
  // Flies the next runs with their log or summary-only (a campaign keeps the logs of a few runs).
  // Throws thetad::Error when the log would not fit in memory (SimulationSettings::validate).
  void set_keep_log(bool keep);

  // The controller of `spec`, designed for the scenario's initial state. Errors name the settings
  // file and field. The controller refers to model(): the Flight must outlive it.
  PreparedController prepare(const ControllerSpec& spec) const;

  // Flies `prepared` through the scenario (it is reset first), showing progress on `progress`
  // under `heading` ("LABEL:" when empty). `observe`, when given, is called with the simulated time
  // as often as the progress display (sim::kProgressSamples): a front end's own display, or its
  // way to stop the flight, by throwing (Python's Ctrl-C): what it throws ends the flight and
  // propagates out of fly(), with no result.
  RunResult fly(PreparedController& prepared, Progress* progress = nullptr, const std::string& heading = {},
                const std::function<void(double t)>& observe = {}) const;

  // The score J_dev of one run (docs/model.md §7.2) on the flight's trims, fresh; none, and
  // `why_not` says why, for a plant without trims or a reference beyond them.
  std::optional<sim::DeviationCost> deviation_cost(std::string& why_not) const;

 private:
  Flight() = default;
  // The helicopter through `parsed` (no plant named).
  Flight(const Scenario& parsed, const RunControls& controls);
  // `plant` regulated to the origin from scenario.initial_state, as the scenario (a file's or the
  // one of_plant makes) and the controls say; scenario.plant is its name.
  static Flight plant_flight(std::shared_ptr<const SdcPlant> plant, Scenario scenario, const RunControls& controls);
  // The columns of a run's log: what SimulationSettings::check_memory needs.
  std::size_t log_width() const;

  Provenance provenance_;
  Scenario scenario_;
  sim::SimulationSettings settings_;
  Eigen::VectorXd initial_state_;
  std::shared_ptr<const SdcPlant> plant_;
  const heli::Helicopter* helicopter_ = nullptr;  // plant_ when it is the helicopter
  // The trims every controller of this flight that asks for them shares (designed at the first ask).
  std::shared_ptr<SharedTrims> trims_ = std::make_shared<SharedTrims>();
};

}  // namespace thetad
