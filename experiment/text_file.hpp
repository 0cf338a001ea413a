#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace thetad {

// The bytes of `file`. Throws thetad::Error naming the file and the system's reason.
std::string read_text_file(const std::filesystem::path& file);

// `file` parsed as JSON. Throws thetad::Error naming the file (unreadable, or not valid JSON).
nlohmann::ordered_json read_json_file(const std::filesystem::path& file);

}  // namespace thetad
