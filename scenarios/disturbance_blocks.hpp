#pragma once

#include <optional>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "core/sim/simulation_settings.hpp"

namespace thetad {

// The blocks of a scenario's `simulation:` for the disturbances beyond the paper (docs/model.md
// §15; docs/scenarios.md shows them): `wind:`, `sensor_noise:` and `servos:`. An absent block is
// nullopt (thetad's default: off); every field of a present block is checked, and an error is a
// SettingsError naming the field and the reason.
struct DisturbanceBlocks {
  std::optional<sim::TurbulenceSettings> turbulence;
  std::optional<std::vector<sim::DiscreteGust>> discrete_gusts;
  std::optional<sim::SensorNoiseSettings> sensor_noise;
  std::optional<sim::ServoSettings> servos;

  // `settings` with every block given here in place of its own.
  void apply(sim::SimulationSettings& settings) const;
};

// The three blocks' nodes (an undefined node for an absent block).
DisturbanceBlocks read_disturbance_blocks(const YAML::Node& wind, const YAML::Node& sensor_noise,
                                          const YAML::Node& servos);

}  // namespace thetad
