// The scenario loader and the trajectories it builds: a scenario that loads must give a finite
// reference position over its whole duration and simulation settings that validate.
#include <cmath>

#include "fuzz/target.hpp"
#include "scenarios/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return thetad::fuzz::run(data, size, [](const std::string& text) {
    const thetad::Scenario scenario = thetad::parse_scenario(text, "fuzz-scenario.yaml");
    const thetad::sim::SimulationSettings settings = scenario.simulation_settings();
    settings.validate();
    for (int i = 0; i <= 16; ++i) {
      const double t = settings.duration * i / 16.0;
      if (!scenario.trajectory.position(t).allFinite())
        thetad::fuzz::finding("a loaded scenario with a non-finite reference", "t = " + std::to_string(t));
    }
  });
}
