#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "controllers/controller.hpp"
#include "core/helicopter/helicopter.hpp"

namespace thetad {

// What a controller is designed with: the model it knows (nominal parameters, no wind: spec A-27)
// and the initial state of the run (t0, xa(t0): spec §7.1).
struct ControllerContext {
  const heli::Helicopter& model;
  Eigen::VectorXd initial_state;
  double initial_time = 0.0;
};

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
