#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "controllers/controller.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/registry.hpp"
#include "settings/settings.hpp"

namespace thetad {

// The plant's trims along a flight's reference, designed by the first controller that asks and
// then shared: every controller of a flight flies the same trims (docs/model.md §7.1).
class SharedTrims {
 public:
  // The plant's trims along `reference` (SdcPlant::trim_source), designed at the first call; null
  // when the plant has none.
  std::shared_ptr<const TrimSource> get(const SdcPlant& plant, const ReferenceTrajectory& reference, double duration,
                                        double period);

 private:
  std::mutex mutex_;
  bool designed_ = false;
  std::shared_ptr<const TrimSource> source_;
};

// What a controller is designed with: the plant it knows (for the helicopter the nominal
// parameters, no wind: docs/model.md §11 ), the design defaults its settings start from and the initial
// state of the run (t0, xa(t0): docs/model.md §8.1). θ–D and SDRE need nothing but an SdcPlant; a
// controller that needs the helicopter's specifics asks helicopter_of().
struct ControllerContext {
  const SdcPlant& plant;
  DesignDefaults defaults;          // plant.design_defaults() unless the caller chose others
  Eigen::VectorXd initial_state;
  double initial_time = 0.0;
  // The run's commanded trajectory, its duration and the controller period (s), when the caller
  // knows them (a Flight does; null otherwise): a controller with a bounded envelope checks it
  // against the command before anything flies. The trajectory must outlive the context.
  const ReferenceTrajectory* reference = nullptr;
  double duration = 0.0;
  double controller_period = 0.0;
  // True when the caller only checks the settings (ControllerRegistry::check): a factory may then
  // return nullptr once it has read every field, skipping a costly design.
  bool settings_only = false;
  // Where trims() keeps what it designed; a caller that builds several controllers for one flight
  // gives them one (a Flight does).
  std::shared_ptr<SharedTrims> shared_trims = std::make_shared<SharedTrims>();

  // The plant's trims along the reference (a hold of the initial state's position without one),
  // designed at the first call. Throws thetad::Error when the plant has no trims.
  std::shared_ptr<const TrimSource> trims() const;

  // Keeps a reference to `plant`: it must outlive the context and the controllers built with it.
  ControllerContext(const SdcPlant& plant, Eigen::VectorXd initial_state, double initial_time = 0.0);
  ControllerContext(const SdcPlant& plant, DesignDefaults defaults, Eigen::VectorXd initial_state,
                    double initial_time = 0.0);
};

// The helicopter behind `context`, for a controller that needs its specifics (trims); throws
// thetad::Error naming `controller` when the plant is another one.
const heli::Helicopter& helicopter_of(const ControllerContext& context, const std::string& controller);

// Builds a controller from its settings block. Every field is read through `settings` (a map;
// null means all defaults), which records the value used, default or given: the registry hands
// that record back (BuiltController::settings). Unknown or ill-typed fields throw
// thetad::SettingsError naming the field (and the line, when the node has one).
using ControllerFactory =
    std::function<std::unique_ptr<Controller>(const Settings& settings, const ControllerContext& context)>;

struct BuiltController {
  std::unique_ptr<Controller> controller;
  // Every field as used, defaults included: building again from it gives the same controller.
  YAML::Node settings;
};

// The controllers thetad knows by name. Each controller registers itself from its own source file
// with a static ControllerRegistration, so adding one touches no other file.
class ControllerRegistry : public Registry<ControllerFactory> {
 public:
  static ControllerRegistry& instance();

  // make() and build() throw thetad::Error listing the known names when `name` is unknown.
  std::unique_ptr<Controller> make(const std::string& name, const YAML::Node& settings,
                                   const ControllerContext& context) const;
  BuiltController build(const std::string& name, const YAML::Node& settings, const ControllerContext& context) const;
  // Reads `settings` as build() would and throws the same errors, but designs nothing where the
  // factory honours ControllerContext::settings_only: for the blocks of a settings file that a
  // run does not fly, so that a typo there is found now and not by the next run that flies it.
  void check(const std::string& name, const YAML::Node& settings, const ControllerContext& context) const;

 private:
  ControllerRegistry() : Registry("controller") {}
};

// `interface_version` is left to its default: it records the version the registering code (a
// plug-in) was built against. The name must be the one the built controllers give (their name(),
// or it plus a variant's suffix): ControllerRegistry::build refuses any other. A controller class
// derived from NamedController is registered with register_controller<C>, which takes the name from
// the class; this constructor is for names chosen at run time (one class under several names).
struct ControllerRegistration {
  ControllerRegistration(const std::string& name, const std::string& description, ControllerFactory factory,
                         int interface_version = kPluginInterfaceVersion) {
    ControllerRegistry::instance().add(name, description, std::move(factory), interface_version);
  }
};

// Registers the controller class C (a NamedController) under its name:
//   const ControllerRegistration registration = register_controller<MyController>("what it is", make_mine);
template <class C>
ControllerRegistration register_controller(const std::string& description, ControllerFactory factory,
                                           int interface_version = kPluginInterfaceVersion) {
  return ControllerRegistration(C::kName, description, std::move(factory), interface_version);
}

}  // namespace thetad
