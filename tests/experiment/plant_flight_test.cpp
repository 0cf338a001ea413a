// A user's plant (not the helicopter) flown by θ–D and the SDRE through the experiment library.
#include "experiment/plant_flight.hpp"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tests/controllers/scalar_plant.hpp"
#include "tests/error_message.hpp"
#include "tests/test_plants.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;

RunControls seconds(double duration) {
  RunControls controls;
  controls.duration = duration;
  return controls;
}

const FixedPosition kOrigin(Eigen::Vector3d::Zero());

// On a linear plant every θ–D term beyond T0 vanishes: θ–D is the LQR, whose cost from x0 is
// ½ x0ᵀ P x0. xdot = x + u, Q = R = 1 (the plant's design defaults): P = 1 + √2.
TEST(PlantFlight, ThetaDOnALinearPlantCostsWhatTheRiccatiSolutionSays) {
  const testing::ScalarPlant plant([](double) { return 1.0; }, [](double, double) { return 1.0; }, false);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.5);
  for (const char* spec : {"theta-d", "sdre"}) {
    const PlantFlightResult flown = fly_plant(plant, parse_controller_spec(spec), x0, kOrigin, seconds(20.0));
    ASSERT_EQ(flown.run.status, sim::RunStatus::completed) << flown.run.reason;
    const double expected = 0.5 * (1.0 + std::sqrt(2.0)) * 0.25;
    // Left rectangles of a decay e^(−√2 t) at 1 ms: relative error ~ √2 · 1 ms / 2.
    EXPECT_NEAR(flown.run.cost, expected, 1e-3 * expected) << spec;
    EXPECT_EQ(flown.run.controller_samples, 20000);
    EXPECT_NEAR(flown.run.log(19999, 1), 0.0, 1e-9) << spec;  // the state decayed
    EXPECT_EQ(flown.settings["Q"][0].as<double>(), 1.0);       // the plant's defaults, recorded
  }
}

// The nonlinear companion plant: θ–D and the SDRE both bring it to rest from (1, 0), with costs
// close to each other (θ–D approximates the SDRE's P).
TEST(PlantFlight, ThetaDAndSdreRegulateANonlinearPlant) {
  const CompanionPlant plant;
  const Eigen::Vector2d x0(1.0, 0.0);
  const PlantFlightResult theta_d = fly_plant(plant, parse_controller_spec("theta-d"), x0, kOrigin, seconds(15.0));
  const PlantFlightResult sdre = fly_plant(plant, parse_controller_spec("sdre"), x0, kOrigin, seconds(15.0));
  for (const auto* flown : {&theta_d, &sdre}) {
    ASSERT_EQ(flown->run.status, sim::RunStatus::completed) << flown->run.reason;
    EXPECT_LT(flown->run.log.row(flown->run.log.rows() - 1).segment(1, 2).norm(), 1e-3);
  }
  EXPECT_NEAR(theta_d.run.cost, sdre.run.cost, 0.05 * sdre.run.cost);
}

TEST(PlantFlight, ControllersThatNeedTheHelicopterAndBadRunsAreClear) {
  const CompanionPlant plant;
  EXPECT_THAT(testing::error_message([&] {
                fly_plant(plant, parse_controller_spec("lqr"), Eigen::Vector2d(1, 0), kOrigin, seconds(1.0));
              }),
              HasSubstr("lqr: flies only the X-Cell helicopter"));
  EXPECT_THAT(testing::error_message([&] {
                fly_plant(plant, parse_controller_spec("theta-d"), Eigen::Vector3d(1, 0, 0), kOrigin, seconds(1.0));
              }),
              HasSubstr("3"));
  EXPECT_THAT(testing::error_message([&] {
                fly_plant(plant, parse_controller_spec("theta-d"), Eigen::Vector2d(1, 0), kOrigin, RunControls{});
              }),
              HasSubstr("must give a duration"));
  // A plant the controller cannot stabilize (no input authority): the SDRE's CARE fails at the first
  // sample and the run ends there, as failed (the controller's fault), with the reason.
  const testing::ScalarPlant uncontrollable([](double) { return 5.0; }, [](double, double) { return 0.0; }, false);
  const PlantFlightResult flown =
      fly_plant(uncontrollable, parse_controller_spec("sdre"), Eigen::VectorXd::Ones(1), kOrigin, seconds(10.0));
  EXPECT_EQ(flown.run.status, sim::RunStatus::failed);
  EXPECT_THAT(flown.run.reason, HasSubstr("controller failed"));
  EXPECT_EQ(flown.run.controller_samples, 0);
}

// The open loop of an unstable plant leaves the state bound and ends the run there, with its time.
TEST(PlantFlight, AStateBeyondTheBoundEndsTheRun) {
  const testing::ScalarPlant unstable([](double) { return 5.0; }, [](double, double) { return 1.0; }, false);
  ConstantInput nothing(Eigen::VectorXd::Zero(1));
  sim::SimulationSettings settings = sim::SimulationSettings::ideal();
  settings.duration = 10.0;
  const sim::PlantRun run = sim::simulate_plant(nothing, unstable, kOrigin, Eigen::VectorXd::Ones(1), settings);
  EXPECT_EQ(run.status, sim::RunStatus::diverged);
  EXPECT_THAT(run.reason, HasSubstr("beyond"));
  EXPECT_NEAR(run.end_time, std::log(1e6) / 5.0, 2e-3);  // e^(5 t) = 1e6
  EXPECT_EQ(run.log.rows(), run.controller_samples);
}

}  // namespace
}  // namespace thetad
