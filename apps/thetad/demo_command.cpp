#include "apps/thetad/demo_command.hpp"

#include <cstdio>

#include "core/atomic_file.hpp"
#include "experiment/demo_diagnostics.hpp"

namespace thetad::app {

int run_demo(const std::filesystem::path& out) {
  const DemoDiagnostics diagnostics = demo_diagnostics();
  std::fputs(demo_text(diagnostics).c_str(), stdout);
  const auto path = out / "demo.json";
  write_file_atomically(path, demo_json(diagnostics).dump(2) + "\n");
  std::printf("wrote %s\n", path.c_str());
  return 0;
}

}  // namespace thetad::app
