#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "experiment/flight.hpp"
#include "settings/run_controls.hpp"

namespace thetad::app {

// Exit codes of the commands that fly: every run completed, or at least one diverged or failed.
inline constexpr int kExitCompleted = 0;
inline constexpr int kExitDiverged = 3;
// thetad run --replay: the run flown again differs from the recorded one.
inline constexpr int kExitReplayDiffers = 4;

// The options `run` and `compare` share.
struct FlightOptions {
  std::string scenario;            // a file, or the name of a shipped scenario
  std::filesystem::path settings;  // empty: every controller with its defaults
  std::string plant;                  // a registered plant instead of a scenario (add_plant_options)
  std::vector<double> initial_state;  // for the plant; empty: its own
  RunControls controls;
  bool quiet = false;
  std::filesystem::path out;
};

// A seed given as `option`: an unsigned 64-bit decimal, whole; "-1", "" or a number beyond
// 2^64 - 1 are CLI11 validation errors naming the option, not wraps.
std::uint64_t parse_seed(const std::string& text, const std::string& option = "--seed");

// Adds --scenario, --settings, every run setting's own option (settings/run_settings.hpp: --seed,
// --ideal, --duration, --dt, ...; those for run files, --log-every, --summary-only and --no-timing,
// only for a command that writes runs), --set, --quiet and --out to `command`.
void add_flight_options(CLI::App& command, FlightOptions& options, bool scenario_required = true,
                        bool writes_runs = true);

// Adds --plant and --initial-state: the shorthand for a scenario file that names a plant
// (docs/plants.md), for the commands that build their flight with flight_of().
void add_plant_options(CLI::App& command, FlightOptions& options);

// The flight of --scenario or --plant (one of them) with `controls`.
Flight flight_of(const FlightOptions& options, const RunControls& controls);

// --controllers (required): specs parsed by parse_controller_specs, `all` included.
CLI::Option* add_controllers_option(CLI::App& command, std::vector<std::string>& controllers);
// --jobs: flights at once; 0 (the default) is every core.
CLI::Option* add_jobs_option(CLI::App& command, int& jobs, const std::string& what = "Flights at once");
// `jobs`, or every core for 0.
int jobs_or_every_core(int jobs);

struct RunArguments {
  FlightOptions flight;
  std::string controller;
  std::filesystem::path replay;
};
CLI::App* add_run_command(CLI::App& app, RunArguments& arguments);
// thetad run: one controller, <out>/<label>.csv and .json, a summary paragraph on stdout.
int run_run(const RunArguments& arguments);

// thetad list: the registered controllers with their descriptions.
int run_list();

}  // namespace thetad::app
