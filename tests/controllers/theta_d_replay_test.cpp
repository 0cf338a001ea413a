// The helicopter's θ–D step replayed on the states the simulator handed θ–D in scenario I,
// against the same u computed otherwise: on dynamic-size types (the generic step), and from the
// series written out with S1, S2 and G0 as n×n matrices and one Lyapunov solve per piece
// (series_expansion, the tuner's cold path) instead of control()'s T1 basis, low-rank sums
// (C_j = Y_j + Z_{j−1}), reuse between passes and last term on the input rows only.
#include <algorithm>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "controllers/theta_d.hpp"
#include "core/helicopter/helicopter.hpp"
#include "tests/controllers/every_pass_settings.hpp"
#include "tests/controllers/scenario_one_flight.hpp"
#include "tests/controllers/theta_d_reference_law.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// The worst relative difference of u over a replay, recorded in the test's output and bounded.
void expect_within_rounding(double worst, int passes) {
  std::ostringstream printed;
  printed << std::scientific << worst;
  ::testing::Test::RecordProperty("worst_relative_difference_passes_" + std::to_string(passes), printed.str());
  EXPECT_LE(worst, 1e-12) << passes << " passes";
}

TEST(ThetaDFixedSize, SameControlAsTheDynamicSizePathOnScenarioOneStates) {
  // The helicopter's step on fixed-size types is the generic one compiled for n = 18, m = 5: the
  // same u to rounding, step after step along the states the simulator handed θ–D in scenario I,
  // with the one-step lag and with the 3-pass fixed point (every pass run).
  const auto& flight = testing::scenario_one_flight();
  for (const int passes : {1, 3}) {
    ThetaDSettings s = testing::every_pass_settings<ThetaDSettings>(flight.model, passes);
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
    expect_within_rounding(worst, passes);
  }
}

TEST(ThetaDReference, ControlEqualsTheWrittenOutSeriesOnScenarioOneStates) {
  const auto& flight = testing::scenario_one_flight();
  for (const int passes : {1, 3}) {
    ThetaDController controller(flight.model, testing::every_pass_settings<ThetaDSettings>(flight.model, passes));
    controller.reset(flight.scenario.initial_state, 0.0);
    VectorXd u(heli::kInputDim), v(heli::kStateDim), previous = controller.settings().initial_input;
    double worst = 0.0;
    for (std::size_t k = 0; k < flight.samples.size(); ++k) {
      const sim::ControlSample& sample = flight.samples[k];
      controller.control(sample.t, sample.state, sample.reference, u);
      // Every third state: the written-out series solves five Lyapunov equations per pass.
      if (k % 3 == 0) {
        flight.model.tracking_vector(sample.state, sample.reference, v);
        const VectorXd expected =
            testing::reference_control(controller, flight.model, sample.state, previous, v, sample.t, passes);
        worst = std::max(worst, (u - expected).norm() / expected.norm());
      }
      previous = u;
    }
    expect_within_rounding(worst, passes);
  }
}

}  // namespace
}  // namespace thetad
