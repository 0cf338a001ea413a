// Anti-windup (docs/model.md §12): with the actuator limits on, at samples where a magnitude bound
// holds the thrust, the position-error integral a controller sees is held; off, it winds up.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/sim/helicopter_disturbances.hpp"
#include "core/sim/recording_law.hpp"
#include "core/trim.hpp"

namespace thetad::sim {
namespace {

using namespace heli;

// Asks for 400 N of thrust, beyond the 213 N bound, and climbs away from a held command.
std::vector<ControlSample> climb_at_the_bound(bool anti_windup) {
  Eigen::VectorXd u(kInputDim);
  u << 400.0, 0.0, 0.0, 0.0, 0.0;
  ConstantInput pull(u);
  std::vector<ControlSample> samples;
  RecordingLaw law(pull, 0.0, samples);
  SimulationSettings settings = SimulationSettings::ideal();
  settings.actuator_limits = ActuatorLimits::x_cell();
  settings.actuator_limits.anti_windup = anti_windup;
  settings.duration = 0.5;
  settings.measure_compute_time = false;
  const Eigen::VectorXd x0 = find_trim(Helicopter(), TrimCondition::hover(3.5)).state;
  const RunResult run = simulate(law, FixedPosition(x0.segment<3>(kXp)), x0, settings);
  EXPECT_EQ(run.summary.saturation.magnitude[kTmr], static_cast<std::int64_t>(samples.size()));
  return samples;
}

TEST(AntiWindup, HoldsTheIntegralErrorWhileTheThrustIsAtItsBound) {
  for (const ControlSample& s : climb_at_the_bound(true))
    ASSERT_EQ((s.state.segment<3>(kXi) - s.reference.integral).norm(), 0.0) << "t = " << s.t;
}

TEST(AntiWindup, OffTheIntegralErrorWindsUp) {
  const std::vector<ControlSample> samples = climb_at_the_bound(false);
  const ControlSample& last = samples.back();
  // Climbing ~ a metre in half a second: the altitude error's integral grows (z down, negative).
  EXPECT_LT(last.state[kZi] - last.reference.integral.z(), -0.01);
}

}  // namespace
}  // namespace thetad::sim
