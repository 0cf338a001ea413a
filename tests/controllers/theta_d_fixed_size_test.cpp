// The helicopter's θ–D step on fixed-size types against the generic dynamic-size step.
#include <algorithm>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "controllers/theta_d.hpp"
#include "core/helicopter/helicopter.hpp"
#include "tests/controllers/scenario_one_flight.hpp"

namespace thetad {
namespace {

using Eigen::VectorXd;

TEST(ThetaDFixedSize, SameControlAsTheDynamicSizePathOnScenarioOneStates) {
  // The helicopter's step on fixed-size types is the generic one compiled for n = 18, m = 5: the
  // same u to rounding, step after step along the states the simulator handed θ–D in scenario I,
  // with the one-step lag and with the 3-pass fixed point (every pass run).
  const auto& flight = testing::scenario_one_flight();
  const DesignDefaults defaults = flight.model.design_defaults();
  for (const int passes : {1, 3}) {
    ThetaDSettings s;
    s.Q = defaults.state_weights.asDiagonal();
    s.R = defaults.input_weights.asDiagonal();
    s.initial_input = defaults.input;
    s.fixed_point_iterations = passes;
    s.fixed_point_tolerance = 0.0;
    ThetaDController fixed_size(flight.model, s);
    s.fixed_size = false;
    ThetaDController dynamic_size(flight.model, s);
    fixed_size.reset(flight.scenario.initial_state, 0.0);
    dynamic_size.reset(flight.scenario.initial_state, 0.0);
    VectorXd u_fixed(heli::kInputDim), u_dynamic(heli::kInputDim);
    double worst = 0.0;
    for (const sim::ControlSample& sample : flight.samples) {
      fixed_size.control(sample.t, sample.state, sample.reference, u_fixed);
      dynamic_size.control(sample.t, sample.state, sample.reference, u_dynamic);
      worst = std::max(worst, (u_fixed - u_dynamic).norm() / u_dynamic.norm());
    }
    std::ostringstream printed;
    printed << std::scientific << worst;
    RecordProperty("worst_relative_difference_passes_" + std::to_string(passes), printed.str());
    EXPECT_LE(worst, 1e-12) << passes << " passes";
  }
}

}  // namespace
}  // namespace thetad
