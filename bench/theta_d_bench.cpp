// One θ–D control step on the helicopter near hover: N = 1 … 4 terms, the exact Ω fixed point
// (3 passes, spec §7.6) against the one-step-lag variant (1 pass). The controller is warm: each
// timed step starts from the input applied at the previous one, as in a closed loop at 1 kHz.

#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include "controllers/theta_d.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/helicopter/paper_weights.hpp"

namespace {

using thetad::heli::kStateDim;

void theta_d_step(benchmark::State& state) {
  namespace heli = thetad::heli;
  const heli::Helicopter model;
  thetad::ThetaDSettings settings;
  settings.terms = static_cast<int>(state.range(0));
  settings.fixed_point_iterations = static_cast<int>(state.range(1));
  settings.fixed_point_tolerance = 0.0;  // always run every pass: the cost of the variant itself
  settings.Q = heli::paper_state_weights().asDiagonal();
  settings.R = heli::paper_input_weights().asDiagonal();
  settings.initial_input = Eigen::VectorXd::Unit(heli::kInputDim, heli::kTmr) *
                           (model.parameters().mass * model.parameters().gravity);
  thetad::ThetaDController controller(model, settings);
  controller.reset(Eigen::VectorXd::Unit(kStateDim, heli::kS), 0.0);

  // Hover-ish: 3.5 m up, drifting slowly, slightly tilted.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kStateDim);
  x[heli::kZp] = -3.5;
  x.segment<3>(heli::kU) << 0.3, -0.1, 0.05;
  x.segment<3>(heli::kPhi) << 0.08, -0.02, 0.05;
  x.segment<3>(heli::kP) << 0.02, -0.01, 0.03;
  x.segment<2>(heli::kA1) << 0.002, 0.008;
  x[heli::kS] = 1.0;
  thetad::sim::Reference reference;
  reference.position << 0.0, 0.0, -3.5;
  Eigen::VectorXd u(heli::kInputDim);
  controller.control(1.0, x, reference, u);

  double t = 1.0;
  for (auto _ : state) {
    t += 1e-3;
    controller.control(t, x, reference, u);
    benchmark::DoNotOptimize(u.data());
  }
  state.counters["passes"] = controller.last_iterations();
}

BENCHMARK(theta_d_step)
    ->ArgNames({"terms", "passes"})
    ->ArgsProduct({{1, 2, 3, 4}, {1, 3}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
