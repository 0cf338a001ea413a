#include "experiment/builtin_plants.hpp"

#include <memory>

#include "core/tora_plant.hpp"

namespace thetad {

void register_builtin_plants(PlantRegistry& registry) {
  registry.add(
      "tora",
      "the RTAC/TORA benchmark of Bupp, Bernstein & Coppola (1998): a cart on a spring driven through a rotating "
      "eccentric mass (4 states, 1 input; settings: epsilon, default 0.2)",
      [](const Settings& settings) {
        settings.allow_only({"epsilon"});
        // The benchmark's regulation problem starts with the cart displaced, everything else at rest.
        return NamedPlant{std::make_unique<ToraPlant>(settings.number("epsilon", 0.2)), Eigen::Vector4d(1.0, 0.0, 0.0, 0.0)};
      },
      kPluginInterfaceVersion);
}

}  // namespace thetad
