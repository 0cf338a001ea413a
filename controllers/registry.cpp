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

ControllerRegistry::OriginScope::OriginScope(std::string origin)
    : previous_(std::exchange(instance().origin_, std::move(origin))), previously_scoped_(std::exchange(instance().scoped_, true)) {}

ControllerRegistry::OriginScope::~OriginScope() {
  instance().origin_ = std::move(previous_);
  instance().scoped_ = previously_scoped_;
}

std::vector<std::string> ControllerRegistry::take_refusals() { return std::exchange(refusals_, {}); }

void ControllerRegistry::add(const std::string& name, const std::string& description, ControllerFactory factory) {
  const auto same = [&](const Entry& e) { return e.name == name; };
  const auto taken = std::find_if(entries_.begin(), entries_.end(), same);
  if (taken != entries_.end()) {
    const std::string refusal = "controller registry: the name '" + name + "' is registered twice (" + taken->origin +
                                " and " + origin_ + ")";
    // Inside an OriginScope the registration runs in a plug-in's static initialization, where an
    // exception would end the program: the loader reports it (take_refusals) instead.
    if (scoped_) {
      refusals_.push_back(refusal);
      return;
    }
    throw Error(refusal);
  }
  entries_.push_back({name, description, origin_, std::move(factory)});
}

const ControllerRegistry::Entry& ControllerRegistry::entry(const std::string& name) const {
  for (const Entry& e : entries_) {
    if (e.name == name) return e;
  }
  throw Error("unknown controller '" + escaped_utf8(name) + "' (known: " + known_names() + ")");
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

bool ControllerRegistry::contains(const std::string& name) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
}

std::string ControllerRegistry::known_names() const {
  std::string known;
  for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
  return known;
}

std::vector<std::string> ControllerRegistry::names() const {
  std::vector<std::string> result;
  for (const Entry& e : entries_) result.push_back(e.name);
  std::sort(result.begin(), result.end());
  return result;
}

const std::string& ControllerRegistry::description(const std::string& name) const { return entry(name).description; }

const std::string& ControllerRegistry::origin(const std::string& name) const { return entry(name).origin; }

}  // namespace thetad
