#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace thetad {

// One file of export/onboard/ as text (embedded at build time by cmake/embed_onboard.cmake).
struct OnboardSource {
  std::string_view file;  // its name in export/onboard/
  std::string_view text;
};
const std::vector<OnboardSource>& onboard_sources();

// The text of export/onboard/FILE; throws thetad::Error for a file that was not embedded.
std::string_view onboard_source(std::string_view file);

// The same without its `#pragma once` line: for concatenation into one header.
std::string onboard_source_inline(std::string_view file);

}  // namespace thetad
