#include "experiment/plugins.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <set>
#include <sstream>
#include <string>

#include "controllers/registry.hpp"
#include "experiment/plant_registry.hpp"
#include "core/error.hpp"
#include "experiment/sha256.hpp"

namespace thetad {

namespace fs = std::filesystem;

void load_plugin(const fs::path& library) {
  static std::mutex mutex;
  static std::set<fs::path> loaded;
  const std::lock_guard lock(mutex);
  std::error_code error;
  const fs::path file = fs::canonical(library, error);
  if (error) throw Error("plug-in " + library.string() + ": " + error.message());
  if (loaded.count(file) > 0) return;
  // The registrations run inside dlopen(): the scope names where they come from.
  {
    // The digest makes results name the very library that flew (provenance: the controller's origin).
    const RegistrationOrigin origin("plug-in " + file.string() + " (sha256 " + sha256_of_file(file) + ")");
    // RTLD_NOW: a symbol the program does not provide is an error now, not a crash mid-flight.
    if (dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL) == nullptr)
      throw Error("cannot load plug-in " + file.string() + ": " + dlerror());
  }
  loaded.insert(file);
  std::vector<std::string> refused = ControllerRegistry::instance().take_refusals();
  for (auto& refusal : PlantRegistry::instance().take_refusals()) refused.push_back(std::move(refusal));
  if (!refused.empty()) throw Error("plug-in " + file.string() + ": " + refused.front());
}

std::vector<fs::path> plugins_from_environment() {
  std::vector<fs::path> libraries;
  const char* path = std::getenv("THETAD_PLUGIN_PATH");
  if (path == nullptr) return libraries;
  std::istringstream entries(path);
  for (std::string entry; std::getline(entries, entry, ':');) {
    if (entry.empty()) continue;
    std::error_code error;
    if (fs::is_directory(entry, error)) {
      std::vector<fs::path> found;
      for (const auto& item : fs::directory_iterator(entry))
        if (item.path().extension() == ".so") found.push_back(item.path());
      std::sort(found.begin(), found.end());
      libraries.insert(libraries.end(), found.begin(), found.end());
    } else if (fs::exists(entry, error)) {
      libraries.emplace_back(entry);
    } else {
      throw Error("THETAD_PLUGIN_PATH: " + entry + " does not exist");
    }
  }
  return libraries;
}

}  // namespace thetad
