#include "controllers/registry.hpp"

#include <algorithm>
#include <utility>

#include "core/error.hpp"
#include "core/text_file.hpp"

namespace thetad {

ControllerContext::ControllerContext(const SdcPlant& plant, Eigen::VectorXd initial_state, double initial_time)
    : ControllerContext(plant, plant.design_defaults(), std::move(initial_state), initial_time) {}

ControllerContext::ControllerContext(const SdcPlant& plant, DesignDefaults defaults, Eigen::VectorXd initial_state,
                                     double initial_time)
    : plant(plant), defaults(std::move(defaults)), initial_state(std::move(initial_state)), initial_time(initial_time) {}

std::shared_ptr<const TrimSource> SharedTrims::get(const SdcPlant& plant, const ReferenceTrajectory& reference,
                                                   double duration, double period) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!designed_) {
    source_ = plant.trim_source(reference, duration, period);
    designed_ = true;
  }
  return source_;
}

std::shared_ptr<const TrimSource> ControllerContext::trims() const {
  std::shared_ptr<const TrimSource> source =
      reference ? shared_trims->get(plant, *reference, duration, controller_period)
                : shared_trims->get(plant, FixedPosition(plant.tracked_position(initial_state)), 0.0, 1.0);
  if (!source)
    throw Error("feedforward velocity+trim: this plant has no trims (SdcPlant::trim_source); use none or velocity");
  return source;
}

const heli::Helicopter& helicopter_of(const ControllerContext& context, const std::string& controller) {
  if (const auto* helicopter = dynamic_cast<const heli::Helicopter*>(&context.plant)) return *helicopter;
  throw Error(controller + ": flies only the X-Cell helicopter (heli::Helicopter), whose trims it is designed at; "
              "this plant is another SdcPlant (n = " + std::to_string(context.plant.state_dim()) +
              ", m = " + std::to_string(context.plant.input_dim()) + ")");
}

ControllerRegistry& ControllerRegistry::instance() {
  // A function-local static: registrations run during static initialization of other
  // translation units, whose order relative to a namespace-scope registry is unspecified.
  static ControllerRegistry registry;
  return registry;
}

std::unique_ptr<Controller> ControllerRegistry::make(const std::string& name, const YAML::Node& settings,
                                                     const ControllerContext& context) const {
  return build(name, settings, context).controller;
}

BuiltController ControllerRegistry::build(const std::string& name, const YAML::Node& settings,
                                          const ControllerContext& context) const {
  const Entry& found = entry(name);
  check_block(settings, name);
  const Settings fields(settings);
  std::unique_ptr<Controller> controller = found.factory(fields, context);
  if (!controller) throw Error("controller '" + name + "' (" + found.origin + "): its factory returned no controller");
  // A run records name(); a variant may add a suffix ("sdre-warm"), nothing else, so that the
  // result names what the user asked for.
  const std::string called = controller->name();
  if (called != name && !called.starts_with(name + "-"))
    throw Error("controller '" + escaped_utf8(name) + "' (" + found.origin + ") built a controller that calls itself '" +
                escaped_utf8(called) + "': derive it from NamedController<\"" + escaped_utf8(name) +
                "\"> and register it with register_controller (controllers/registry.hpp)");
  return {std::move(controller), fields.resolved()};
}

void ControllerRegistry::check(const std::string& name, const YAML::Node& settings,
                               const ControllerContext& context) const {
  ControllerContext checking = context;
  checking.settings_only = true;
  const Entry& found = entry(name);
  check_block(settings, name);
  found.factory(Settings(settings), checking);
}

}  // namespace thetad
