#pragma once

#include <filesystem>
#include <vector>

namespace thetad {

// A plug-in is a shared library whose static ControllerRegistrations add controllers to the
// program that loads it (and may register anything else that registers itself). It is built
// against the installed headers with thetad_add_plugin() (cmake/thetadPlugin.cmake) and links
// none of thetad's libraries: the program provides them, so the registrations reach the
// program's one registry. `thetad list` shows each controller's origin.

// Loads `library` (once; loading it again does nothing). Throws thetad::Error naming the file and
// the loader's reason (a missing file, a missing symbol, a controller name already taken).
void load_plugin(const std::filesystem::path& library);

// The plug-ins THETAD_PLUGIN_PATH names: ':'-separated files, or folders whose *.so files are
// taken in name order. Throws thetad::Error for an entry that does not exist.
std::vector<std::filesystem::path> plugins_from_environment();

}  // namespace thetad
