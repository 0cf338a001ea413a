#include "experiment/plant_registry.hpp"

#include "core/text_file.hpp"
#include "experiment/builtin_plants.hpp"

namespace thetad {

PlantRegistry::PlantRegistry() : Registry("plant") { register_builtin_plants(*this); }

PlantRegistry& PlantRegistry::instance() {
  // Function-local: registrations run during the static initialization of other files.
  static PlantRegistry registry;
  return registry;
}

NamedPlant PlantRegistry::make(const std::string& name, const YAML::Node& settings) const {
  const Entry& found = entry(name);
  check_block(settings, name);
  return found.factory(Settings(settings));
}

}  // namespace thetad
