#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "core/registry.hpp"
#include "core/sdc_plant.hpp"
#include "settings/settings.hpp"

namespace thetad {

// A plant of the user's, by name, for `thetad run --plant NAME`: a plug-in registers it (with a
// static PlantRegistration, as controllers register themselves), and θ–D and the SDRE fly it.
struct NamedPlant {
  std::unique_ptr<SdcPlant> plant;
  Eigen::VectorXd initial_state;  // where a flight starts unless told otherwise
};
using PlantFactory = std::function<NamedPlant(const Settings& settings)>;

class PlantRegistry : public Registry<PlantFactory> {
 public:
  static PlantRegistry& instance();
  // The plant `name` built from its settings block (null: every default). Throws thetad::Error
  // listing the known names when `name` is unknown.
  NamedPlant make(const std::string& name, const YAML::Node& settings) const;

 private:
  PlantRegistry();
};

// As ControllerRegistration: `interface_version` records the version the plug-in was built against.
struct PlantRegistration {
  PlantRegistration(const std::string& name, const std::string& description, PlantFactory factory,
                    int interface_version = kPluginInterfaceVersion) {
    PlantRegistry::instance().add(name, description, std::move(factory), interface_version);
  }
};

}  // namespace thetad
