// The weights design (docs/weights.md) on a small envelope (hover and 5 m/s forward and sideways):
// Bryson's start, checks that hold after the adjustment for every controller at 1 kHz and 100 Hz,
// the same weights every time, and a request that cannot be met reported as such.
#include "controllers/weights_design.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "core/helicopter/state.hpp"

namespace thetad {
namespace {

WeightDesignInputs small_envelope() {
  WeightDesignInputs inputs;
  inputs.envelope.speeds = {0.0, 5.0};
  inputs.envelope.courses = {0.0, std::numbers::pi / 2};
  inputs.envelope.climb_rates = {0.0};
  return inputs;
}

TEST(WeightsDesign, StartsFromBrysonsRuleOnTheExcursionsAndTheHeadroom) {
  WeightDesignInputs inputs = small_envelope();
  inputs.max_adjustments = 0;
  const WeightDesign design = design_weights(heli::Helicopter(), inputs);
  EXPECT_DOUBLE_EQ(design.state_weights[heli::kXp], 1.0 / (0.5 * 0.5));
  EXPECT_DOUBLE_EQ(design.state_weights[heli::kPsi], 1.0 / (0.1 * 0.1));
  EXPECT_EQ(design.state_weights[heli::kS], 0.0);
  // Thrust: hover (~80.5 N) down to 0 is the smaller side of [0, 213 N].
  EXPECT_NEAR(design.headroom[heli::kTmr], 80.5, 0.5);
  EXPECT_DOUBLE_EQ(design.input_weights[heli::kTmr], 1.0 / (design.headroom[heli::kTmr] * design.headroom[heli::kTmr]));
  EXPECT_FALSE(design.holds);  // the paper-like start asks for ~3x the thrust headroom on a 1 m step
  EXPECT_FALSE(design.unmet.empty());
}

TEST(WeightsDesign, AdjustsUntilEveryControllersSampledLoopHoldsTheSameWayEveryTime) {
  const WeightDesign design = design_weights(heli::Helicopter(), small_envelope());
  ASSERT_TRUE(design.holds);
  EXPECT_TRUE(design.unmet.empty());
  ASSERT_EQ(design.checks.size(), 8u);  // four controllers at 1 kHz and 100 Hz
  for (const WeightCheck& check : design.checks) {
    EXPECT_LT(check.spectral_radius, 1.0) << check.controller << " " << check.period;
    EXPECT_GE(check.disk_margin, 0.3) << check.controller << " " << check.period;
    EXPECT_LE(check.peak_input_share, 0.8) << check.controller << " " << check.period;
  }
  const WeightDesign again = design_weights(heli::Helicopter(), small_envelope());
  EXPECT_EQ(again.state_weights, design.state_weights);
  EXPECT_EQ(again.input_weights, design.input_weights);
  const std::string text = weights_settings_text(design);
  for (const char* block : {"\ntheta-d:\n", "\nsdre:\n", "\nlqr:\n", "\nlqr-scheduled:\n"})
    EXPECT_NE(text.find(block), std::string::npos) << block;
}

TEST(WeightsDesign, SaysWhatCannotBeMet) {
  WeightDesignInputs inputs = small_envelope();
  inputs.headroom_share = 1e-4;  // no response can stay this close to hover
  inputs.max_adjustments = 3;
  const WeightDesign design = design_weights(heli::Helicopter(), inputs);
  EXPECT_FALSE(design.holds);
  ASSERT_FALSE(design.unmet.empty());
  EXPECT_NE(weights_settings_text(design).find("NOT MET"), std::string::npos);
}

}  // namespace
}  // namespace thetad
