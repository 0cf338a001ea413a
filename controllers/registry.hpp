#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "controllers/controller.hpp"
#include "core/helicopter/helicopter.hpp"

namespace thetad {

// What a controller is designed with: the plant it knows (for the helicopter the nominal
// parameters, no wind: spec A-27), the design defaults its settings start from and the initial
// state of the run (t0, xa(t0): spec §7.1). θ–D and SDRE need nothing but an SdcPlant; a
// controller that needs the helicopter's specifics asks helicopter_of().
struct ControllerContext {
  const SdcPlant& plant;
  DesignDefaults defaults;          // plant.design_defaults() unless the caller chose others
  Eigen::VectorXd initial_state;
  double initial_time = 0.0;

  // Keeps a reference to `plant`: it must outlive the context and the controllers built with it.
  ControllerContext(const SdcPlant& plant, Eigen::VectorXd initial_state, double initial_time = 0.0);
  ControllerContext(const SdcPlant& plant, DesignDefaults defaults, Eigen::VectorXd initial_state,
                    double initial_time = 0.0);
};

// The helicopter behind `context`, for a controller that needs its specifics (trims); throws
// thetad::Error naming `controller` when the plant is another one.
const heli::Helicopter& helicopter_of(const ControllerContext& context, const std::string& controller);

// Builds a controller from its settings block (a YAML map; null means all defaults). Unknown or
// ill-typed fields throw thetad::Error naming the field (and the line, when the node has one).
using ControllerFactory =
    std::function<std::unique_ptr<Controller>(const YAML::Node& settings, const ControllerContext& context)>;

// The controllers thetad knows by name. Each controller registers itself from its own source file
// with a static ControllerRegistration, so adding one touches no other file.
class ControllerRegistry {
 public:
  static ControllerRegistry& instance();

  void add(const std::string& name, const std::string& description, ControllerFactory factory);
  // Throws thetad::Error listing the known names when `name` is unknown.
  std::unique_ptr<Controller> make(const std::string& name, const YAML::Node& settings,
                                   const ControllerContext& context) const;
  std::vector<std::string> names() const;
  const std::string& description(const std::string& name) const;

 private:
  struct Entry {
    std::string name;
    std::string description;
    ControllerFactory factory;
  };
  std::vector<Entry> entries_;
};

struct ControllerRegistration {
  ControllerRegistration(const std::string& name, const std::string& description, ControllerFactory factory) {
    ControllerRegistry::instance().add(name, description, std::move(factory));
  }
};

}  // namespace thetad
