#include "experiment/plant_registry.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/text_file.hpp"

namespace thetad {

PlantRegistry& PlantRegistry::instance() {
  // Function-local: registrations run during the static initialization of other files.
  static PlantRegistry registry;
  return registry;
}

void PlantRegistry::add(const std::string& name, const std::string& description, PlantFactory factory) {
  const auto same = [&](const Entry& e) { return e.name == name; };
  if (std::any_of(entries_.begin(), entries_.end(), same))
    throw Error("plant registry: the name '" + name + "' is registered twice");
  entries_.push_back({name, description, std::move(factory)});
}

const PlantRegistry::Entry& PlantRegistry::entry(const std::string& name) const {
  for (const Entry& e : entries_)
    if (e.name == name) return e;
  std::string known;
  for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown plant '" + escaped_utf8(name) + "' (known: " + (known.empty() ? "none; a plug-in registers plants" : known) +
              ")");
}

NamedPlant PlantRegistry::make(const std::string& name, const YAML::Node& settings) const {
  const Entry& found = entry(name);
  check_block(settings, name);
  return found.factory(Settings(settings));
}

std::vector<std::string> PlantRegistry::names() const {
  std::vector<std::string> result;
  for (const Entry& e : entries_) result.push_back(e.name);
  std::sort(result.begin(), result.end());
  return result;
}

const std::string& PlantRegistry::description(const std::string& name) const { return entry(name).description; }

}  // namespace thetad
