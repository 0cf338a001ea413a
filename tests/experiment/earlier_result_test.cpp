// A result written by an earlier build flies again to the same figures: this one by thetad at
// 779336f, before the feed-forward settings and J_dev existed (hover-to-hover, θ–D, seed 1, 2 s,
// summary-only; tests/fixtures/results). Its settings leave feedforward out, which is `none`, and
// it recorded the scenario's text, so an edit of the shipped file does not change the replay.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "experiment/replay.hpp"

namespace thetad {
namespace {

TEST(EarlierResult, FliesAgainToTheSameCost) {
  const Replay replayed =
      replay(std::string(THETAD_SOURCE_DIR) + "/tests/fixtures/results/hover-to-hover-theta-d-779336f.json");
  constexpr double kRecordedJ = 7243.411607772617;
  EXPECT_LE(std::abs(replayed.result.summary.cost - kRecordedJ), 1e-9 * kRecordedJ);
  for (const std::string& difference : replayed.differences) ADD_FAILURE() << difference;
  EXPECT_TRUE(replayed.result.summary.cost_dev.has_value());
}

}  // namespace
}  // namespace thetad
