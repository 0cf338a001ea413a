#pragma once

#include <nlohmann/json.hpp>

#include "core/sim/simulation_settings.hpp"
#include "settings/disturbance_blocks.hpp"

namespace thetad {

// What acts beyond the paper (docs/model.md §15) in a result's "settings": "turbulence",
// "discrete_gusts", "sensor_noise", "servos" and "computer", field names with units.
void write_beyond_paper(const sim::SimulationSettings& settings, nlohmann::ordered_json& json);

// The same read back from a result's "settings", every block set: a block the file does not
// have was not there when it was written, and such runs flew without it (the defaults, off).
// Throws nlohmann's exceptions on a malformed block.
DisturbanceBlocks read_beyond_paper(const nlohmann::ordered_json& json);

}  // namespace thetad
