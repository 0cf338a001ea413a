// J_dev needs the flight's trims; a reference beyond them (faster than 20 m/s) still flies, and its
// result says why it has no J_dev instead of failing the run (docs/model.md §7.2).
#include <gtest/gtest.h>

#include <string>

#include "experiment/flight.hpp"

namespace thetad {
namespace {

TEST(DeviationScore, AReferenceBeyondTheTrimsFliesWithoutJDevAndSaysWhy) {
  const char* const dash = R"(name: dash
duration: 1
initial_state:
  position: [0, 0, 3.5]
phases:
  - name: dash
    type: ramp
    time: [0, 1]
    to: [25, 0, 3.5]
)";
  RunControls controls;
  controls.ideal = true;
  controls.timing = false;
  controls.summary_only = true;
  const Flight flight = Flight::from_text(dash, "dash.yaml", controls);
  PreparedController prepared = flight.prepare({"lqr", "lqr", YAML::Node(), "", {}});
  const RunResult result = flight.fly(prepared);
  EXPECT_FALSE(result.summary.cost_dev.has_value());
  EXPECT_EQ(result.summary.cost_dev_weights.rfind("none: trims: the reference commands 25 m/s", 0), 0u)
      << result.summary.cost_dev_weights;
  EXPECT_GT(result.summary.controller_samples, 0);
}

}  // namespace
}  // namespace thetad
