#include "export/onboard_sources.hpp"

#include "core/error.hpp"

namespace thetad {

std::string_view onboard_source(std::string_view file) {
  for (const OnboardSource& source : onboard_sources())
    if (source.file == file) return source.text;
  throw Error("export: export/onboard/" + std::string(file) + " was not embedded in this build");
}

std::string onboard_source_inline(std::string_view file) {
  std::string text(onboard_source(file));
  const std::string pragma = "#pragma once\n";
  if (const std::size_t at = text.find(pragma); at != std::string::npos) text.erase(at, pragma.size());
  return text;
}

}  // namespace thetad
