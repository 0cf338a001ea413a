#include "experiment/plant_flight.hpp"

#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "settings/settings.hpp"

namespace thetad {

PlantFlightResult fly_plant(const SdcPlant& plant, const ControllerSpec& spec, const Eigen::VectorXd& x0,
                            const ReferenceTrajectory& reference, const RunControls& controls) {
  if (!controls.duration) throw Error("fly_plant: the run controls must give a duration");
  sim::SimulationSettings settings = sim::SimulationSettings::ideal();
  apply(controls, settings);
  const ControllerContext context(plant, x0, 0.0);
  auto build = [&] { return ControllerRegistry::instance().build(spec.controller, spec.settings, context); };
  BuiltController built = spec.settings_source.empty() ? build() : with_settings_source(spec.settings_source, build);
  return {spec, built.settings, sim::simulate_plant(*built.controller, plant, reference, x0, settings)};
}

}  // namespace thetad
