#include "experiment/scenario_files.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>

#include "core/error.hpp"
#include "core/text_file.hpp"
#include "experiment/build_config.hpp"

namespace thetad {

namespace fs = std::filesystem;

std::vector<fs::path> data_directories() {
  std::vector<fs::path> folders;
  if (const char* given = std::getenv("THETAD_DATA_DIR"); given != nullptr && *given != '\0') folders.emplace_back(given);
  // The binary holding this code (the program, or a shared module linking the library) locates
  // the installed data the way the install laid it out.
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&data_directories), &info) != 0 && info.dli_fname != nullptr) {
    std::error_code error;
    const fs::path binary = fs::canonical(info.dli_fname, error);
    if (!error) folders.push_back((binary.parent_path() / THETAD_DATA_FROM_BIN).lexically_normal());
  }
  folders.emplace_back(THETAD_SOURCE_DATA);
  return folders;
}

std::vector<std::string> shipped_names(const std::string& folder) {
  std::error_code error;
  for (const fs::path& data : data_directories()) {
    if (!fs::is_directory(data / folder, error)) continue;
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(data / folder, error)) {
      const std::string file = entry.path().filename().string();
      if (entry.is_regular_file(error) && entry.path().extension() == ".yaml" && !file.ends_with(".settings.yaml"))
        names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }
  return {};
}

fs::path find_shipped(const std::string& file_or_name, const std::string& folder, const std::string& kind) {
  std::error_code error;
  if (fs::is_regular_file(file_or_name, error)) return file_or_name;
  const fs::path given(file_or_name);
  std::string looked;
  if (!file_or_name.empty() && given.is_relative()) {
    const fs::path file = given.extension() == ".yaml" ? given : fs::path(file_or_name + ".yaml");
    for (const fs::path& data : data_directories()) {
      const fs::path candidate = data / folder / file;
      if (fs::is_regular_file(candidate, error)) return candidate;
      looked += (looked.empty() ? "" : ", ") + (data / folder).string();
    }
  }
  // A name from the command line may hold any bytes; the message must still be UTF-8.
  const std::string name = escaped_utf8(file_or_name);
  if (fs::exists(given, error)) throw Error(kind + " " + name + ": not a regular file");
  std::string shipped;
  for (const std::string& known : shipped_names(folder)) shipped += (shipped.empty() ? "" : ", ") + known;
  throw Error(kind + " '" + name + "': no such file" +
              (looked.empty() ? std::string()
                              : ", nor a shipped " + kind + " of that name (shipped: " + shipped + "; looked in " +
                                    looked + ")"));
}

fs::path find_scenario(const std::string& file_or_name) { return find_shipped(file_or_name, "scenarios", "scenario"); }

fs::path find_campaign(const std::string& file_or_name) {
  return find_shipped(file_or_name, "scenarios/campaigns", "campaign");
}

}  // namespace thetad
