#pragma once

#include "experiment/plant_registry.hpp"

namespace thetad {

// The plants thetad ships besides the helicopter (which flies through scenarios): registered when
// the registry is made, so that no linker can drop them from a static library.
void register_builtin_plants(PlantRegistry& registry);

}  // namespace thetad
