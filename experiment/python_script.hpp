#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace thetad {

// Debian's interpreter (/usr/bin/python3: the one that sees python3-matplotlib, pandas and scipy,
// whatever python3 is first on PATH), or $THETAD_PYTHON.
std::string python_interpreter();

// A script shipped with thetad (scripts/NAME): the installed one for an installed thetad (it must
// not depend on the source tree it was built from), the source tree's for a build.
std::filesystem::path shipped_script(const std::string& name);

// Runs `python script arguments...` with MPLBACKEND=Agg and returns its exit status. Its stdout and
// stderr go to `log`, or to thetad's own when `log` is empty.
int run_python_script(const std::filesystem::path& script, const std::vector<std::string>& arguments,
                      const std::filesystem::path& log = {});

}  // namespace thetad
