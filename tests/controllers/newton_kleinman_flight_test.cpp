// Newton–Kleinman warm-started as the SDRE uses it: from the solution at another state of a flight
// (scenario I, recorded), the SDC F(x), B(x) of the helicopter at the state it is asked about.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include <Eigen/Dense>

#include "core/riccati.hpp"
#include "tests/controllers/scenario_one_flight.hpp"
#include "tests/core/care_checks.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;

TEST(NewtonKleinmanOnAFlight, WarmStartsFromTheSolutionAtAnotherState) {
  const auto& flight = testing::scenario_one_flight();
  const DesignDefaults defaults = flight.model.design_defaults();
  const MatrixXd Q = defaults.state_weights.asDiagonal();
  const MatrixXd R = defaults.input_weights.asDiagonal();
  const auto sdc_at = [&](std::size_t k) {
    const sim::ControlSample& s = flight.samples[k];
    return flight.model.sdc(s.state, s.input);
  };
  const std::size_t last = flight.samples.size() - 1;
  // From the previous sample (the SDRE's warm step), from 0.1 s earlier and from the other end of
  // the recording (1 s apart).
  for (const auto& [from, to] : {std::pair<std::size_t, std::size_t>{last - 1, last}, {last - 100, last}, {0, last},
                                 {last, 0}}) {
    SCOPED_TRACE("from sample " + std::to_string(from) + " to " + std::to_string(to));
    const SdcPlant::Coefficients start = sdc_at(from);
    const SdcPlant::Coefficients target = sdc_at(to);
    const MatrixXd P0 = solve_care(start.F, start.B, Q, R).P;
    const CareResult result = solve_care_newton(target.F, target.B, Q, R, P0);
    testing::expect_valid_care(target.F, target.B, Q, R, result);
    const MatrixXd direct = solve_care(target.F, target.B, Q, R).P;
    EXPECT_LE((result.P - direct).norm(), 1e-9 * direct.norm());
    EXPECT_LE(result.iterations, 8);
  }
}

}  // namespace
}  // namespace thetad
