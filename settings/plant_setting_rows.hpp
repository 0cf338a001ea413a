#pragma once

#include <vector>

#include "settings/run_settings.hpp"

namespace thetad {

// The rows of the run settings' table that a plant's flight has and the helicopter's refuses: the
// factor families plant.NAME (its settings) and initial_state.I (its start), docs/campaigns.md.
std::vector<RunSetting> plant_setting_rows();

}  // namespace thetad
