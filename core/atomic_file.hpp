#pragma once

#include <filesystem>
#include <string>

namespace thetad {

// Writes `content` to `path` through a temporary file in the same directory that is renamed onto
// `path` only once it is complete, so a reader never sees half a file. Creates the directory if
// needed. Throws thetad::Error naming the path and the reason; no temporary file is left behind.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

}  // namespace thetad
