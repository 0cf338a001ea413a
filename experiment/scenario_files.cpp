#include "experiment/scenario_files.hpp"

#include <dlfcn.h>

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

fs::path find_scenario(const std::string& file_or_name) {
  std::error_code error;
  if (fs::is_regular_file(file_or_name, error)) return file_or_name;
  const fs::path given(file_or_name);
  std::string looked;
  if (!file_or_name.empty() && !given.has_parent_path()) {
    const std::string file = given.extension() == ".yaml" ? file_or_name : file_or_name + ".yaml";
    for (const fs::path& folder : data_directories()) {
      const fs::path candidate = folder / "scenarios" / file;
      if (fs::is_regular_file(candidate, error)) return candidate;
      looked += (looked.empty() ? "" : ", ") + (folder / "scenarios").string();
    }
  }
  // A name from the command line may hold any bytes; the message must still be UTF-8.
  const std::string name = escaped_utf8(file_or_name);
  if (fs::exists(given, error)) throw Error("scenario " + name + ": not a regular file");
  throw Error("scenario '" + name + "': no such file" +
              (looked.empty() ? std::string() : ", nor a shipped scenario of that name (looked in " + looked + ")"));
}

}  // namespace thetad
