#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace thetad {

// `file` parsed as JSON. Throws thetad::Error naming the file (unreadable, not a regular file, too
// large, or not valid JSON).
nlohmann::ordered_json read_json_file(const std::filesystem::path& file);

}  // namespace thetad
