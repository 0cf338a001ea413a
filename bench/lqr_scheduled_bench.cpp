// One control step of the gain-scheduled LQR at n = 18: the blend of the 8 surrounding grid points'
// trims and gains (5×17 each) and u = u* − K (V − V*). The reference moves so that every step
// schedules between grid points in all three variables.
#include <benchmark/benchmark.h>

#include <memory>

#include <yaml-cpp/yaml.h>

#include "controllers/lqr_scheduled.hpp"
#include "core/trim.hpp"

namespace {

void BM_LqrScheduledControl(benchmark::State& state) {
  const thetad::heli::Helicopter model;
  // A small grid keeps the smoke run quick; the step's cost does not depend on the grid's size.
  const thetad::LqrScheduleGrid grid = thetad::read_lqr_grid(thetad::Settings(
      YAML::Load("{speeds: [0, 2, 4], courses_deg: [0, 90, 180, 270], climb_rates: [-0.5, 0, 0.5]}")));
  const thetad::DesignDefaults defaults = model.design_defaults();
  const auto table = std::make_shared<thetad::LqrScheduleTable>(
      thetad::design_lqr_schedule(model, grid, defaults.state_weights, defaults.input_weights));
  thetad::LqrScheduledController controller(model, table);
  const thetad::Trim trim = thetad::find_trim(model, thetad::TrimCondition::straight(3.0, 0.5, 0.25, 3.5));
  Eigen::VectorXd measured = trim.state;
  measured(0) += 0.1;
  const Eigen::Vector3d velocity(3.0 * std::cos(0.5), 3.0 * std::sin(0.5), -0.25);
  controller.reset(trim.state, 0.0);
  thetad::Reference reference;
  reference.position = trim.state.segment<3>(0);
  Eigen::VectorXd u(thetad::heli::kInputDim);
  double t = 0.0;
  for (auto _ : state) {
    t += 1e-3;
    reference.position += velocity * 1e-3;
    controller.control(t, measured, reference, u);
    benchmark::DoNotOptimize(u.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_LqrScheduledControl);

}  // namespace

BENCHMARK_MAIN();
