// The simulator with the disturbances beyond the paper's (docs/model.md §15): no allocation per
// sample with every one on, the servo chain's order in a flight, and the paper's draws unchanged
// when the later sources are switched on.
#include "core/sim/simulator.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include <gtest/gtest.h>

#include "core/sim/helicopter_disturbances.hpp"
#include "core/sim/seed.hpp"
#include "core/sim/servo_dynamics.hpp"
#include "tests/core/hover_trim.hpp"
#include "tests/heap_counter.hpp"

namespace thetad::sim {
namespace {

using thetad::testing::hover_trim_input;
using thetad::testing::hover_trim_state;
using thetad::testing::kHoverPoint;

// Every disturbance on, the paper's and those beyond it, the controller at every step: from the
// second sample on (the first may size lazily initialized library state), no sample allocates.
TEST(Simulator, StepLoopDoesNotAllocate) {
  class CountingHold final : public ControlLaw {
   public:
    std::string name() const override { return "counting_hold"; }
    void reset(const Eigen::VectorXd&, double) override { calls = 0; }
    void control(double, const Eigen::Ref<const Eigen::VectorXd>&, const Reference&,
                 Eigen::Ref<Eigen::VectorXd> u) override {
      counts[calls++] = thetad::testing::heap_allocations.load(std::memory_order_relaxed);
      u = hover_trim_input_storage;
    }
    Eigen::VectorXd hover_trim_input_storage = hover_trim_input();
    std::array<long, 200> counts{};
    std::size_t calls = 0;
  } hold;
  SimulationSettings paper = SimulationSettings::paper();
  paper.duration = 0.2;
  SimulationSettings beyond = paper;
  beyond.turbulence.model = TurbulenceSettings::Model::dryden;
  beyond.discrete_gusts = {{1, 0.5, 0.05, 0.1}};
  beyond.sensor_noise.density.setConstant(1e-5);
  beyond.sensor_noise.bias.setConstant(1e-4);
  beyond.servos.time_constant.setConstant(0.02);
  beyond.servos.delay_samples = 2;
  for (const SimulationSettings& settings : {paper, beyond}) {
    RunResult result;
    const long allocations = thetad::testing::heap_allocations_during(
        [&] { result = simulate(hold, kHoverPoint, hover_trim_state(), settings); });
    if (allocations < 0) GTEST_SKIP() << "malloc cannot be interposed in this build (AddressSanitizer)";
    ASSERT_EQ(result.summary.status, RunStatus::completed) << result.summary.reason;
    ASSERT_EQ(hold.calls, 200u);
    EXPECT_GT(allocations, 0);  // the counter sees allocations (the run's log, before the loop)
    EXPECT_EQ(hold.counts[199], hold.counts[1]);
  }
}

// A command that changes every sample: trim plus a small wave on every input.
class WavingTrim final : public ControlLaw {
 public:
  std::string name() const override { return "waving_trim"; }
  void reset(const Eigen::VectorXd&, double) override {}
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>&, const Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    u = trim_;
    u.array() += 1e-3 * std::sin(40.0 * t);
  }

 private:
  Eigen::VectorXd trim_ = hover_trim_input();
};

// The servo chain's order (docs/model.md §15.5) in a flight: without noise and limits, the applied
// input is the command of `delay` samples before (the first one until then), then lagged.
TEST(Simulator, ServoChainDelaysThenLags) {
  SimulationSettings settings = SimulationSettings::ideal();
  settings.duration = 0.05;
  settings.servos.delay_samples = 3;
  WavingTrim law;
  const RunResult delayed = simulate(law, kHoverPoint, hover_trim_state(), settings);
  const Eigen::Index command = helicopter_log_column("cmd_T_mr_N"), applied = helicopter_log_column("app_T_mr_N");
  const auto at = [&](const RunResult& run, Eigen::Index row, Eigen::Index column) {
    return run.log.values[static_cast<std::size_t>(row) * run.log.columns.size() + static_cast<std::size_t>(column)];
  };
  for (Eigen::Index k = 0; k < 50; ++k)
    EXPECT_EQ(at(delayed, k, applied), at(delayed, std::max<Eigen::Index>(k - 3, 0), command)) << k;

  settings.servos.time_constant.setConstant(0.01);
  const RunResult lagged = simulate(law, kHoverPoint, hover_trim_state(), settings);
  ServoLag lag(Eigen::VectorXd::Constant(1, 0.01), settings.controller_period());
  for (Eigen::Index k = 0; k < 50; ++k) {
    Eigen::VectorXd input = Eigen::VectorXd::Constant(1, at(delayed, k, applied));
    lag.apply(input);
    EXPECT_EQ(at(lagged, k, applied), input[0]) << k;
  }
}

// The later sources draw from their own streams: switching them on leaves the paper's draws
// (here the Table 1 parameters and the relative measurement noise of a held state) as they were.
TEST(Simulator, NewSourcesLeaveThePaperDrawsAsTheyWere) {
  SimulationSettings paper = SimulationSettings::paper();
  paper.duration = 0.02;
  paper.seed = 17;
  SimulationSettings beyond = paper;
  beyond.turbulence.model = TurbulenceSettings::Model::gauss_markov;
  beyond.turbulence.sigma.setConstant(0.3);
  beyond.servos.delay_samples = 1;
  ConstantInput hold(hover_trim_input());
  const RunResult a = simulate(hold, kHoverPoint, hover_trim_state(), paper);
  const RunResult b = simulate(hold, kHoverPoint, hover_trim_state(), beyond);
  EXPECT_EQ(a.summary.parameter_factors, b.summary.parameter_factors);
  const Eigen::Index measured_phi = helicopter_log_column("meas_phi_rad");
  EXPECT_EQ(a.log.values[static_cast<std::size_t>(measured_phi)], b.log.values[static_cast<std::size_t>(measured_phi)]);
  EXPECT_NE(stream_seed(17, RandomStream::turbulence), stream_seed(17, RandomStream::sensor_noise));
  EXPECT_NE(stream_seed(17, RandomStream::turbulence), stream_seed(18, RandomStream::turbulence));
}

}  // namespace
}  // namespace thetad::sim
