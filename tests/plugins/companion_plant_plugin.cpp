// A plug-in that registers a plant of its own (the companion oscillator of tests/test_plants.hpp),
// for the command-line test of `thetad run --plant`. Built a second time as if against an older
// plug-in interface (THETAD_TEST_INTERFACE_VERSION), which the program must refuse.
#include <memory>

#include "experiment/plant_registry.hpp"
#include "tests/test_plants.hpp"

namespace {

#ifndef THETAD_TEST_INTERFACE_VERSION
#define THETAD_TEST_INTERFACE_VERSION thetad::kPluginInterfaceVersion
#endif

const thetad::PlantRegistration registration(
    "companion", "Duffing-type oscillator in companion form with a state-dependent input gain (2 states, 1 input)",
    [](const thetad::Settings& settings) {
      settings.allow_only({});
      return thetad::NamedPlant{std::make_unique<thetad::CompanionPlant>(), Eigen::Vector2d(1.0, 0.0)};
    },
    THETAD_TEST_INTERFACE_VERSION);

}  // namespace
