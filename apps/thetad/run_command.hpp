#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <yaml-cpp/yaml.h>

#include "controllers/controller.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/sim/simulator.hpp"
#include "scenarios/scenario.hpp"

namespace thetad::app {

// The options `run` and `compare` share.
struct FlightOptions {
  std::filesystem::path scenario;
  std::filesystem::path settings;  // empty: every controller with its defaults
  std::uint64_t seed = 1;
  bool seed_given = false;  // --seed overrides the scenario's seed, which overrides 1
  bool ideal = false;       // no parameter uncertainty, noise or wind, whatever the scenario says
  std::filesystem::path out;
};

// Adds --scenario, --settings, --seed, --ideal and --out to `command`.
void add_flight_options(CLI::App& command, FlightOptions& options);

// A scenario read and ready to fly, with the controllers' model and settings. Everything that can
// be wrong with the files is found while building it, before anything is flown or written.
class Flight {
 public:
  explicit Flight(const FlightOptions& options);

  const Scenario& scenario() const { return scenario_; }
  const sim::SimulationSettings& settings() const { return settings_; }
  // "paper disturbances" / "ideal" / the switches the scenario changed.
  std::string disturbances() const;

  // The named controller from the registry, designed for the scenario's initial state with its
  // block of the settings file (defaults without one). Errors name the settings file and line.
  std::unique_ptr<Controller> make_controller(const std::string& name) const;

  // Flies `controller` through the scenario, with a progress line on stderr headed by `label`.
  sim::RunResult fly(Controller& controller, const std::string& label) const;

 private:
  Scenario scenario_;
  sim::SimulationSettings settings_;
  // The controllers' model: nominal parameters, the scenario's model options, no wind.
  // Controllers keep a reference to it: it lives as long as the flight.
  heli::Helicopter model_;
  std::string settings_source_;
  YAML::Node controller_settings_;  // map: controller name -> settings block
};

// "completed" or "diverged at 16.200 s".
std::string status_text(const sim::RunSummary& summary);

struct RunArguments {
  FlightOptions flight;
  std::string controller;
};
CLI::App* add_run_command(CLI::App& app, RunArguments& arguments);
// thetad run: one controller, <out>/<controller>.csv and .json, a summary paragraph on stdout.
int run_run(const RunArguments& arguments);

// thetad list: the registered controllers with their descriptions.
int run_list();

}  // namespace thetad::app
