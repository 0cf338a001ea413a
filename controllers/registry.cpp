#include "controllers/registry.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace thetad {

ControllerRegistry& ControllerRegistry::instance() {
  // A function-local static: registrations run during static initialization of other
  // translation units, whose order relative to a namespace-scope registry is unspecified.
  static ControllerRegistry registry;
  return registry;
}

void ControllerRegistry::add(const std::string& name, const std::string& description, ControllerFactory factory) {
  const bool taken = std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
  if (taken) throw Error("controller registry: the name '" + name + "' is registered twice");
  entries_.push_back({name, description, std::move(factory)});
}

std::unique_ptr<Controller> ControllerRegistry::make(const std::string& name, const YAML::Node& settings,
                                                     const ControllerContext& context) const {
  for (const Entry& e : entries_) {
    if (e.name == name) return e.factory(settings, context);
  }
  std::string known;
  for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown controller '" + name + "' (known: " + known + ")");
}

std::vector<std::string> ControllerRegistry::names() const {
  std::vector<std::string> result;
  for (const Entry& e : entries_) result.push_back(e.name);
  std::sort(result.begin(), result.end());
  return result;
}

const std::string& ControllerRegistry::description(const std::string& name) const {
  for (const Entry& e : entries_) {
    if (e.name == name) return e.description;
  }
  throw Error("unknown controller '" + name + "'");
}

}  // namespace thetad
