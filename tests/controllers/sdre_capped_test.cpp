// The SDRE's capped mode: exactly newton_iterations Newton–Kleinman steps per pass from the last P,
// the first sample from the cold solution at the state reset() is given (what the exported step
// stores), its residual logged and its unconverged samples counted, and its settings.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "controllers/registry.hpp"
#include "controllers/sdre.hpp"
#include "core/error.hpp"
#include "tests/controllers/hover_recovery.hpp"
#include "tests/controllers/scalar_plant.hpp"
#include "tests/error_message.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;
using testing::ScalarPlant;

SdreSettings capped(int steps) {
  SdreSettings settings;
  settings.mode = SdreSettings::Mode::capped;
  settings.newton_iterations = steps;
  settings.Q = Eigen::MatrixXd::Ones(1, 1);
  settings.R = Eigen::MatrixXd::Ones(1, 1);
  return settings;
}

// ẋ = x² x + u, q = r = 1: one Newton step from P0 at a = x² solves 2(a − P0)P + 1 + P0² = 0.
double newton_step(double x, double P0) { return (1.0 + P0 * P0) / (2.0 * (P0 - x * x)); }

TEST(SdreCapped, StartsFromTheColdSolutionAtTheResetStateAndTakesExactlyItsSteps) {
  const ScalarPlant plant([](double x) { return x * x; }, [](double, double) { return 1.0; }, false);
  for (const int steps : {1, 2}) {
    SdreController sdre(plant, capped(steps));
    EXPECT_EQ(sdre.name(), "sdre-capped");
    sdre.reset(Eigen::VectorXd::Constant(1, 0.5), 0.0);
    double P = plant.riccati(0.5, 0.0, 1.0, 1.0);  // the design point's P, whatever the first sample
    for (const double x : {0.3, 0.35, 0.4}) {
      for (int k = 0; k < steps; ++k) P = newton_step(x, P);
      EXPECT_NEAR(testing::sdre_control_at(sdre, 0.0, x), -P * x, 1e-14) << steps << " steps, x = " << x;
    }
    EXPECT_EQ(sdre.fallback_count(), 0);
  }
}

TEST(SdreCapped, LogsTheResidualOfEachSampleAndCountsTheUnconverged) {
  const ScalarPlant plant([](double x) { return x * x; }, [](double, double) { return 1.0; }, false);
  SdreController sdre(plant, capped(1));
  sdre.reset(Eigen::VectorXd::Zero(1), 0.0);
  ASSERT_EQ(sdre.log_columns().size(), 1U);
  EXPECT_EQ(sdre.log_columns()[0].column.name, "newton_residual");
  std::vector<double> row;
  testing::sdre_control_at(sdre, 0.0, 0.0);  // at the design point: P is the solution already
  sdre.log_values(row);
  EXPECT_LE(row.at(0), 1e-15);
  testing::sdre_control_at(sdre, 0.001, 0.8);  // one step from far away leaves a residual
  sdre.log_values(row);
  EXPECT_GT(row.at(1), 1e-6);
  const auto counters = sdre.counters();
  ASSERT_EQ(counters.size(), 3U);
  EXPECT_EQ(counters[2].first, "newton_unconverged");
  EXPECT_EQ(counters[2].second, 1.0);
  EXPECT_EQ(sdre.unconverged_count(), 1);
}

TEST(SdreCapped, FallsBackToAColdSolveWhenAStepCannotStart) {
  // At x = 2, a = 4 and a − P(0) = 3 > 0: Newton cannot start from the design point's P.
  const ScalarPlant plant([](double x) { return x * x; }, [](double, double) { return 1.0; }, false);
  SdreController sdre(plant, capped(2));
  sdre.reset(Eigen::VectorXd::Zero(1), 0.0);
  EXPECT_NEAR(testing::sdre_control_at(sdre, 0.0, 2.0), -plant.riccati(2.0, 0.0, 1.0, 1.0) * 2.0, 1e-12);
  EXPECT_EQ(sdre.fallback_count(), 1);
  std::vector<double> row;
  sdre.log_values(row);
  EXPECT_TRUE(std::isnan(row.at(0)));
}

TEST(SdreCapped, SettingsNameNewtonIterationsWhenOutOfRange) {
  const heli::Helicopter model;
  const ControllerContext context{model, testing::hover_trim_at_3_5_m().state, 0.0};
  const auto make = [&](const char* settings) {
    return ControllerRegistry::instance().make("sdre", YAML::Load(settings), context);
  };
  const auto sdre = make("{mode: capped, newton_iterations: 3}");
  EXPECT_EQ(sdre->name(), "sdre-capped");
  EXPECT_EQ(static_cast<const SdreController&>(*sdre).settings().newton_iterations, 3);
  EXPECT_EQ(static_cast<const SdreController&>(*make("{mode: capped}")).settings().newton_iterations, 2);
  for (const char* bad : {"{mode: capped, newton_iterations: 0}", "{mode: capped, newton_iterations: 21}"})
    EXPECT_THAT(testing::error_message([&] { make(bad); }), HasSubstr("newton_iterations")) << bad;
}

// Three steps a pass converge on the hover recovery (ρ ≤ 1e-12 at every sample), so the capped
// mode flies as the warm one does.
TEST(SdreCapped, WithThreeStepsFliesAsTheWarmModeOnAHoverRecovery) {
  const heli::Helicopter model;
  const ControllerContext context{model, testing::hover_trim_at_3_5_m().state, 0.0};
  auto capped_law = ControllerRegistry::instance().make("sdre", YAML::Load("{mode: capped, newton_iterations: 3}"), context);
  auto warm_law = ControllerRegistry::instance().make("sdre", YAML::Load("{mode: warm}"), context);
  const auto capped_run = testing::recover_hover(*capped_law, Eigen::Vector3d(1.0, 0.0, 0.0), 0.5);
  const auto warm_run = testing::recover_hover(*warm_law, Eigen::Vector3d(1.0, 0.0, 0.0), 0.5);
  ASSERT_EQ(capped_run.status, sim::RunStatus::completed) << capped_run.reason;
  EXPECT_NEAR(capped_run.final_error, warm_run.final_error, 1e-9);
  const auto& capped_sdre = static_cast<SdreController&>(*capped_law);
  EXPECT_EQ(capped_sdre.fallback_count(), 0);
  EXPECT_EQ(capped_sdre.unconverged_count(), 0);
}

}  // namespace
}  // namespace thetad
