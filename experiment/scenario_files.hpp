#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace thetad {

// The folders holding thetad's shipped data (scenarios/, the plotting scripts), in the order they
// are searched: $THETAD_DATA_DIR, the installed share/thetad beside the program, the source tree
// of a build that was not installed.
std::vector<std::filesystem::path> data_directories();

// A scenario given as a file, or by the name of a shipped one ("scenario-1", "scenario-1.yaml").
// Throws thetad::Error naming what was looked for and where.
std::filesystem::path find_scenario(const std::string& file_or_name);

}  // namespace thetad
