#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace thetad {

// The folders holding thetad's shipped data (scenarios/, the plotting scripts), in the order they
// are searched: $THETAD_DATA_DIR, the installed share/thetad beside the program, the source tree
// of a build that was not installed.
std::vector<std::filesystem::path> data_directories();

// A file, or the name of a shipped one in <data folder>/`folder` ("scenario-1", "scenario-1.yaml";
// "fair/legs" in a subfolder). Throws thetad::Error naming what was looked for, where, and the
// shipped names; `kind` ("scenario", "campaign") names it in the message.
std::filesystem::path find_shipped(const std::string& file_or_name, const std::string& folder, const std::string& kind);

// The names of the shipped files in the first data folder that has `folder`: its *.yaml but the
// settings files (*.settings.yaml), sorted, without the extension.
std::vector<std::string> shipped_names(const std::string& folder);

// find_shipped for scenarios (scenarios/) and campaign files (scenarios/campaigns/).
std::filesystem::path find_scenario(const std::string& file_or_name);
std::filesystem::path find_campaign(const std::string& file_or_name);

}  // namespace thetad
