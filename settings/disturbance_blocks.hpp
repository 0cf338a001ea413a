#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/sim/simulation_settings.hpp"
#include "settings/settings.hpp"

namespace thetad {

// A thetad bench file whose step times set the flight computer's latency (docs/model.md §15.7),
// and which of its statistics to take: median, p90, p99 or max.
struct StepTimeFile {
  std::filesystem::path file;  // as the scenario names it, resolved against the scenario's folder
  std::string statistic = "median";
};

// The blocks of a scenario's `simulation:` for what acts beyond the paper (docs/model.md §15;
// docs/scenarios.md shows them): the disturbances `wind:`, `sensor_noise:` and `servos:`, and the
// flight computer `computer:`. An absent block is nullopt (thetad's default: off); every field of a
// present block is checked, and an error is a SettingsError naming the field and the reason.
struct DisturbanceBlocks {
  std::optional<sim::TurbulenceSettings> turbulence;
  std::optional<std::vector<sim::DiscreteGust>> discrete_gusts;
  std::optional<sim::SensorNoiseSettings> sensor_noise;
  std::optional<sim::ServoSettings> servos;
  std::optional<sim::FlightComputerSettings> computer;
  // The computer's step times still to be read from a bench file (the experiment layer reads it,
  // with its digest: load_step_times); none when they are given in the block or not needed.
  std::optional<StepTimeFile> step_time_file;

  // `settings` with every block given here in place of its own.
  void apply(sim::SimulationSettings& settings) const;
};

// The four blocks of a scenario's `simulation` block (each absent one nullopt); `folder`: the
// scenario file's, against which a bench file's relative name is resolved.
DisturbanceBlocks read_disturbance_blocks(const Settings& simulation, const std::filesystem::path& folder);

}  // namespace thetad
