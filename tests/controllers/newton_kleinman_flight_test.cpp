// Newton–Kleinman warm-started as the SDRE uses it: from the solution at another state of a flight
// (scenario I, recorded), the SDC F(x), B(x) of the helicopter at the state it is asked about.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdio>
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

// The SDRE's use: one solver from sample to sample, each call warm-started from the last P, over
// the transient at the start of scenario I (where chord steps with a held Schur form once led to a
// destabilizing P), with either proof of stability.
struct Along {
  double worst = 0.0;  // largest distance of a P to the direct solver's, relative
  int calls = 0, steps = 0, schur_forms = 0, certified = 0;
};

Along along_the_flight(StabilityProof proof) {
  const auto& flight = testing::scenario_one_flight();
  const DesignDefaults defaults = flight.model.design_defaults();
  const MatrixXd Q = defaults.state_weights.asDiagonal();
  const MatrixXd R = defaults.input_weights.asDiagonal();
  NewtonKleinmanSolver solver(Q, R, 1e-12, 50, proof);
  CareSolver direct(Q, R);
  const sim::ControlSample& first = flight.samples[0];
  const SdcPlant::Coefficients start = flight.model.sdc(first.state, first.input);
  MatrixXd P = direct.solve(start.F, start.B).P;
  Along along;
  for (std::size_t k = 1; k < flight.samples.size(); ++k) {
    const sim::ControlSample& s = flight.samples[k];
    const SdcPlant::Coefficients sdc = flight.model.sdc(s.state, s.input);
    const CareResult& result = solver.solve(sdc.F, sdc.B, P);
    const MatrixXd& exact = direct.solve(sdc.F, sdc.B).P;
    along.worst = std::max(along.worst, (result.P - exact).norm() / exact.norm());
    ++along.calls;
    along.steps += result.iterations;
    along.schur_forms += solver.last_schur_forms();
    along.certified += solver.last_certified() ? 1 : 0;
    P = result.P;
  }
  return along;
}

void record(const Along& along) {
  ::testing::Test::RecordProperty("calls", along.calls);
  ::testing::Test::RecordProperty("steps", along.steps);
  ::testing::Test::RecordProperty("schur_forms", along.schur_forms);
  ::testing::Test::RecordProperty("certified", along.certified);
  char worst[32];
  std::snprintf(worst, sizeof worst, "%.3g", along.worst);
  ::testing::Test::RecordProperty("largest_distance_to_the_direct_P", worst);
}

// Flown once for both tests below.
const Along& along_the_flight_by_spectrum() {
  static const Along along = along_the_flight(StabilityProof::spectrum);
  return along;
}

// Every P is the direct solver's, and the held Schur forms are in fact reused: Newton steps only
// would take one Schur form per step plus the final one.
TEST(NewtonKleinmanOnAFlight, OneSolverAlongTheFlightReusesItsSchurFormsAndStaysExact) {
  const Along& along = along_the_flight_by_spectrum();
  EXPECT_LE(along.worst, 1e-9);
  EXPECT_LT(along.schur_forms, along.steps);
  EXPECT_EQ(along.certified, 0);
  record(along);
}

// The SDRE's proof: the same accuracy, and the certificate holds at every sample (the paper's
// weights leave Q + PGP far from singular). So every call spares the final Schur form; the held
// one is then older, and a few calls need a Newton step more (on this build 4 of 999, against
// 999 Schur forms spared; the bound leaves room for another compiler's rounding).
TEST(NewtonKleinmanOnAFlight, TheLyapunovCertificateHoldsAlongTheFlightAndSparesSchurForms) {
  const Along& spectrum = along_the_flight_by_spectrum();
  const Along along = along_the_flight(StabilityProof::lyapunov);
  EXPECT_LE(along.worst, 1e-9);
  EXPECT_EQ(along.certified, along.calls);
  EXPECT_LE(along.schur_forms, spectrum.schur_forms - 9 * along.calls / 10);
  record(along);
}

}  // namespace
}  // namespace thetad
