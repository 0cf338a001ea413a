// A plant plug-in: the inverted pendulum (inverted_pendulum.hpp) registered by name, with its
// settings and initial state, for every front end that flies a plant (docs/plants.md):
//   thetad --plugin inverted_pendulum_plugin.so run --plant inverted-pendulum --controller sdre --duration 5 --out out
// or a scenario file with `plant: inverted-pendulum` and `plant_settings: {length: 0.5, damping: 0.2}`.
#include <memory>

#include "experiment/plant_registry.hpp"
// Beside this file, in thetad's tree and in the installed example project alike.
#include "inverted_pendulum.hpp"

namespace {

const thetad::PlantRegistration registration(
    "inverted-pendulum",
    "example plug-in: an inverted pendulum with a torque at its pivot (2 states, 1 input; settings: length in m, "
    "default 1, damping in N m s/rad, default 0.1)",
    [](const thetad::Settings& settings) {
      settings.allow_only({"length", "damping"});
      // Errors name the field and the range: "field 'length': ... outside [0.01, 100]".
      const double length = settings.number("length", 1.0, 0.01, 100.0);
      const double damping = settings.number("damping", 0.1, 0.0, 100.0);
      // Tilted 0.3 rad (17°) from the upright, at rest: where the SDRE and θ–D differ from the LQR.
      return thetad::NamedPlant{std::make_unique<thetad::examples::InvertedPendulum>(length, damping),
                                Eigen::Vector2d(0.3, 0.0)};
    });

}  // namespace
