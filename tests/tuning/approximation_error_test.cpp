// The θ–D's approximation error along a flight: exact where the series is exact (the design
// state, where Ã = 0 and g̃ = 0 leave ΣT_i = T0 = P), the control error in the cost's R-norm, and
// a real SDRE flight of scenario I with the θ–D as shadow.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "controllers/registry.hpp"
#include "controllers/sdre.hpp"
#include "core/error.hpp"
#include "experiment/flight.hpp"
#include "tests/tuning/helicopter_theta_d.hpp"
#include "tuning/approximation_error.hpp"

namespace thetad::tuning {
namespace {

SdreController paper_sdre(const testing::HelicopterThetaD& heli) {
  const auto made = ControllerRegistry::instance().make("sdre", YAML::Node(), ControllerContext{heli.model, heli.x0, 0.0});
  return dynamic_cast<const SdreController&>(*made);
}

TEST(ApproximationError, VanishesAtTheDesignStateAndMeasuresTheControlInTheRNorm) {
  const testing::HelicopterThetaD heli;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(2);
  TuningRecord record = testing::theta_d_targets(heli, ones, ones).record;  // sample 0: x0 at hover input
  record.shadow_inputs = 1.01 * record.inputs;
  const SdreController sdre = paper_sdre(heli);
  const ApproximationError error = approximation_error(sdre, heli.make(3), record, 2);
  ASSERT_EQ(error.frobenius.size(), record.size());
  EXPECT_LT(error.frobenius[0], 1e-9);
  EXPECT_LT(error.sigma[0], 1e-9);
  // Off the design state the three-term series is an approximation.
  EXPECT_GT(error.frobenius[150], 1e-8);
  for (Eigen::Index k = 0; k < record.size(); ++k) EXPECT_NEAR(error.control[k], 0.01, 1e-12) << k;

  const nlohmann::ordered_json summary = approximation_summary(error);
  EXPECT_EQ(summary["samples"], 200);
  EXPECT_EQ(summary["frobenius"]["max"].get<double>(), error.frobenius.maxCoeff());
  EXPECT_LE(summary["frobenius"]["median"].get<double>(), summary["frobenius"]["p90"].get<double>());

  record.shadow_inputs.resize(0, 0);
  EXPECT_THROW(approximation_error(sdre, heli.make(3), record, 1), Error);
}

// Half a second of scenario I: the θ–D's own control, computed in the SDRE's place, is close to
// the SDRE's but not equal (its e_i start at 0).
TEST(ApproximationError, AlongAShortSdreFlightWithTheThetaDAsShadow) {
  RunControls half_second;
  half_second.duration = 0.5;
  half_second.summary_only = true;
  const Flight flight(THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml", half_second);
  const PreparedController sdre = flight.prepare({"sdre", "sdre", {}, {}, {}});
  PreparedController theta_d = flight.prepare({"theta-d", "theta-d", {}, {}, {}});
  const auto& sdre_controller = dynamic_cast<const SdreController&>(*sdre.controller);
  const TuningRecord record = record_sdre_flight(flight, sdre_controller, 10, 2, nullptr, theta_d.controller.get());
  ASSERT_EQ(record.size(), 50);
  ASSERT_EQ(record.shadow_inputs.cols(), 50);
  auto& series = dynamic_cast<ThetaDController&>(*theta_d.controller);
  series.reset(flight.initial_state(), 0.0);
  const ApproximationError error = approximation_error(sdre_controller, series, record, 2);
  EXPECT_GT(error.control.minCoeff(), 0.0);
  EXPECT_LT(error.control.maxCoeff(), 0.1);
  EXPECT_TRUE(error.frobenius.allFinite() && error.sigma.allFinite());
  EXPECT_NE(record.shadow_inputs, record.inputs);
}

}  // namespace
}  // namespace thetad::tuning
