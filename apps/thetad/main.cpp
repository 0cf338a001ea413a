// The thetad command line. Every thetad::Error becomes one clear line on stderr and exit code 1.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "apps/thetad/demo_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"thetad: theta-D, SDRE and LQR control of the X-Cell miniature helicopter"};
  app.require_subcommand(1);

  std::filesystem::path demo_out = "out";
  auto* demo = app.add_subcommand("demo", "Solve the paper-sized Riccati problem and trim the plant; print diagnostics");
  demo->add_option("--out", demo_out, "Output directory")->capture_default_str();

  CLI11_PARSE(app, argc, argv);
  try {
    if (*demo) return thetad::app::run_demo(demo_out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "thetad: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
