// The helicopter's θ–D step (control(): the T1 basis, the low-rank sums of W2 as products of
// C_j = Y_j + Z_{j−1}, the last term on the input rows only) against the series written out with
// S1, S2 and G0 as n×n matrices and one Lyapunov solve per piece (series_expansion, the tuner's
// cold path), on the states the simulator handed θ–D in scenario I.
#include <algorithm>
#include <sstream>
#include <string>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "controllers/theta_d.hpp"
#include "core/helicopter/helicopter.hpp"
#include "tests/controllers/scenario_one_flight.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Eq. (35) on the written-out series: u = −R⁻¹ Bᵀ(x; guess) ΣT_i(x; guess, t) v.
VectorXd reference_law(ThetaDController& controller, const SdcPlant& model, const VectorXd& x, const VectorXd& guess,
                       const VectorXd& v, double t) {
  const ThetaDSettings& s = controller.settings();
  VectorXd e(s.terms - 1);
  for (Eigen::Index i = 0; i < e.size(); ++i) e[i] = perturbation_factor(s.k[i], s.l[i], t - controller.start_time());
  const MatrixXd P = controller.series_expansion(x, guess).evaluate(e);
  const MatrixXd B = model.sdc(x, guess).B;
  return -s.R.llt().solve(B.transpose() * (P * v));
}

TEST(ThetaDReference, ControlEqualsTheWrittenOutSeriesOnScenarioOneStates) {
  const auto& flight = testing::scenario_one_flight();
  const DesignDefaults defaults = flight.model.design_defaults();
  for (const int passes : {1, 3}) {
    ThetaDSettings s;
    s.Q = defaults.state_weights.asDiagonal();
    s.R = defaults.input_weights.asDiagonal();
    s.initial_input = defaults.input;
    s.fixed_point_iterations = passes;
    s.fixed_point_tolerance = 0.0;
    ThetaDController controller(flight.model, s);
    controller.reset(flight.scenario.initial_state, 0.0);
    VectorXd u(heli::kInputDim), v(heli::kStateDim), previous = defaults.input;
    double worst = 0.0;
    for (std::size_t k = 0; k < flight.samples.size(); ++k) {
      const sim::ControlSample& sample = flight.samples[k];
      controller.control(sample.t, sample.state, sample.reference, u);
      // Every third state: the written-out series solves five Lyapunov equations per pass.
      if (k % 3 == 0) {
        flight.model.tracking_vector(sample.state, sample.reference, v);
        VectorXd expected = previous;  // spec §7.6: the fixed point starts from the last input
        for (int pass = 0; pass < passes; ++pass)
          expected = reference_law(controller, flight.model, sample.state, expected, v, sample.t);
        worst = std::max(worst, (u - expected).norm() / expected.norm());
      }
      previous = u;
    }
    std::ostringstream printed;
    printed << std::scientific << worst;
    RecordProperty("worst_relative_difference_passes_" + std::to_string(passes), printed.str());
    EXPECT_LE(worst, 1e-12) << passes << " passes";
  }
}

}  // namespace
}  // namespace thetad
