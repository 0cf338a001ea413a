#pragma once

#include <filesystem>

namespace thetad::app {

// The main job of `make demo`: the foundation of every comparison, with its diagnostics printed
// and written to <out>/demo.json.
int run_demo(const std::filesystem::path& out);

}  // namespace thetad::app
