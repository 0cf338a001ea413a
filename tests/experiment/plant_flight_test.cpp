// A user's plant (not the helicopter) flown by θ–D and the SDRE through the experiment library.
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/plant_code_error.hpp"
#include "experiment/flight.hpp"
#include "tests/controllers/scalar_plant.hpp"
#include "tests/error_message.hpp"
#include "tests/run_seconds.hpp"
#include "tests/test_plants.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;
using testing::seconds;

RunResult fly(std::shared_ptr<const SdcPlant> plant, const char* spec, const Eigen::VectorXd& x0,
              const RunControls& controls) {
  const Flight flight = Flight::of_plant(std::move(plant), "test-plant", x0, controls);
  PreparedController prepared = flight.prepare(parse_controller_spec(spec));
  return flight.fly(prepared);
}

std::shared_ptr<const SdcPlant> scalar_plant(double a, double b) {
  return std::make_shared<testing::ScalarPlant>([a](double) { return a; }, [b](double, double) { return b; }, false);
}

// On a linear plant every θ–D term beyond T0 vanishes: θ–D is the LQR, whose cost from x0 is
// ½ x0ᵀ P x0. xdot = x + u, Q = R = 1 (the plant's design defaults): P = 1 + √2.
TEST(PlantFlight, ThetaDOnALinearPlantCostsWhatTheRiccatiSolutionSays) {
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, 0.5);
  for (const char* spec : {"theta-d", "sdre"}) {
    const RunResult flown = fly(scalar_plant(1.0, 1.0), spec, x0, seconds(20.0));
    ASSERT_EQ(flown.summary.status, sim::RunStatus::completed) << flown.summary.reason;
    const double expected = 0.5 * (1.0 + std::sqrt(2.0)) * 0.25;
    // Left rectangles of a decay e^(−√2 t) at 1 ms: relative error ~ √2 · 1 ms / 2.
    EXPECT_NEAR(flown.summary.cost, expected, 1e-3 * expected) << spec;
    EXPECT_EQ(flown.summary.controller_samples, 20000);
    EXPECT_NEAR(flown.log.row(19999)[1], 0.0, 1e-9) << spec;  // the state decayed
    EXPECT_EQ(flown.settings["Q"][0].as<double>(), 1.0);      // the plant's defaults, recorded
    EXPECT_EQ(flown.provenance.plant, "test-plant");
  }
}

// The nonlinear companion plant: θ–D and the SDRE both bring it to rest from (1, 0), with costs
// close to each other (θ–D approximates the SDRE's P).
TEST(PlantFlight, ThetaDAndSdreRegulateANonlinearPlant) {
  const auto plant = std::make_shared<const CompanionPlant>();
  const Eigen::Vector2d x0(1.0, 0.0);
  const RunResult theta_d = fly(plant, "theta-d", x0, seconds(15.0));
  const RunResult sdre = fly(plant, "sdre", x0, seconds(15.0));
  for (const auto* flown : {&theta_d, &sdre}) {
    ASSERT_EQ(flown->summary.status, sim::RunStatus::completed) << flown->summary.reason;
    EXPECT_LT(flown->log.row(flown->log.rows() - 1).segment(1, 2).norm(), 1e-3);
  }
  EXPECT_NEAR(theta_d.summary.cost, sdre.summary.cost, 0.05 * sdre.summary.cost);
}

// The shipped RTAC/TORA benchmark, from the registry: θ–D and the SDRE bring the displaced cart
// to rest through the rotor alone (its design weights Q = I, R = 1).
TEST(PlantFlight, ThetaDAndSdreRegulateTheToraBenchmark) {
  for (const char* spec : {"theta-d", "sdre"}) {
    const Flight flight = Flight::of_plant("tora", std::nullopt, seconds(30.0));
    PreparedController prepared = flight.prepare(parse_controller_spec(spec));
    const RunResult flown = flight.fly(prepared);
    ASSERT_EQ(flown.summary.status, sim::RunStatus::completed) << spec << ": " << flown.summary.reason;
    const auto last = flown.log.row(flown.log.rows() - 1);
    EXPECT_LT(std::abs(last[1]), 0.05) << spec;  // the cart's position, from 1
    EXPECT_EQ(flown.log.columns[1].header(), "xi");
    EXPECT_EQ(flown.provenance.initial_state, (std::vector<double>{1.0, 0.0, 0.0, 0.0}));
  }
}

// The log and the summary take the plant's shape: its states and inputs, no tracked states.
TEST(PlantFlight, TheLogAndTheSummaryHaveThePlantsShape) {
  const RunResult flown = fly(std::make_shared<const CompanionPlant>(), "theta-d", Eigen::Vector2d(1, 0), seconds(0.1));
  std::vector<std::string> headers;
  for (const auto& column : flown.log.columns) headers.push_back(column.header());
  EXPECT_EQ(headers, (std::vector<std::string>{"t_s", "x_0", "x_1", "meas_x_0", "meas_x_1", "cmd_u_0", "app_u_0",
                                               "in_flight_step_time_ns"}));
  EXPECT_EQ(flown.summary.command_rms.size(), 1);
  EXPECT_EQ(flown.summary.rms_tracking_error.size(), 0);
  EXPECT_EQ(flown.summary.saturation.magnitude.size(), 1u);
}

TEST(PlantFlight, ControllersThatNeedTheHelicopterAndBadRunsAreClear) {
  const auto plant = std::make_shared<const CompanionPlant>();
  EXPECT_THAT(testing::error_message([&] { fly(plant, "lqr-scheduled", Eigen::Vector2d(1, 0), seconds(1.0)); }),
              HasSubstr("lqr-scheduled: flies only the X-Cell helicopter"));
  EXPECT_THAT(testing::error_message([&] { fly(plant, "theta-d", Eigen::Vector3d(1, 0, 0), seconds(1.0)); }),
              HasSubstr("the initial state has 3 entries"));
  EXPECT_THAT(testing::error_message([&] { fly(plant, "theta-d", Eigen::Vector2d(1, 0), RunControls{}); }),
              HasSubstr("needs a duration"));
  RunControls windy = seconds(1.0);
  windy.wind_gust = true;
  EXPECT_THAT(testing::error_message([&] { fly(plant, "theta-d", Eigen::Vector2d(1, 0), windy); }),
              HasSubstr("flies without disturbances or actuator limits"));
  // A plant the controller cannot stabilize (no input authority): the SDRE's CARE fails at the first
  // sample and the run ends there, as failed (the controller's fault), with the reason.
  const RunResult flown = fly(scalar_plant(5.0, 0.0), "sdre", Eigen::VectorXd::Ones(1), seconds(10.0));
  EXPECT_EQ(flown.summary.status, sim::RunStatus::failed);
  EXPECT_THAT(flown.summary.reason, HasSubstr("controller failed"));
  EXPECT_EQ(flown.summary.controller_samples, 0);
}

// The open loop of an unstable plant leaves the state bound and ends the run there, with its time.
TEST(PlantFlight, AStateBeyondTheBoundEndsTheRun) {
  const auto unstable = scalar_plant(5.0, 1.0);
  ConstantInput nothing(Eigen::VectorXd::Zero(1));
  sim::SimulationSettings settings = sim::SimulationSettings::ideal();
  settings.duration = 10.0;
  sim::NoDisturbances as_it_is(*unstable);
  const FixedPosition origin(Eigen::Vector3d::Zero());
  const sim::RunResult run = sim::simulate(nothing, as_it_is, origin, Eigen::VectorXd::Ones(1), settings);
  EXPECT_EQ(run.summary.status, sim::RunStatus::diverged);
  EXPECT_THAT(run.summary.reason, HasSubstr("exceeds 1e+06"));
  EXPECT_NEAR(run.summary.end_time, std::log(1e6) / 5.0, 2e-3);  // e^(5 t) = 1e6
  EXPECT_EQ(run.log.rows(), run.summary.controller_samples);
}

// ẋ = −x + u, whose coefficient throws `Failure` once x falls below 0.5: in f first, within the RK4
// step that crosses it, before any controller sample sees it.
template <class Failure>
std::shared_ptr<const SdcPlant> failing_plant() {
  return std::make_shared<testing::ScalarPlant>(
      [](double x) {
        if (x < 0.5) throw Failure("f gave up");
        return -1.0;
      },
      [](double, double) { return 1.0; }, false);
}

// A plant whose code fails (PlantCodeError: a plant written in Python raised) ends its run as
// failed, the code's fault; any other error of the plant as diverged, the closed loop's.
TEST(PlantFlight, APlantWhoseCodeFailsEndsItsRunAsFailed) {
  const Eigen::VectorXd x0 = Eigen::VectorXd::Ones(1);
  const RunResult failed = fly(failing_plant<PlantCodeError>(), "sdre", x0, seconds(2.0));
  const RunResult diverged = fly(failing_plant<Error>(), "sdre", x0, seconds(2.0));
  EXPECT_EQ(failed.summary.status, sim::RunStatus::failed);
  EXPECT_EQ(diverged.summary.status, sim::RunStatus::diverged);
  for (const auto* flown : {&failed, &diverged}) {
    EXPECT_THAT(flown->summary.reason, HasSubstr("plant failed at t = "));
    EXPECT_THAT(flown->summary.reason, HasSubstr(": f gave up"));
    EXPECT_GT(flown->summary.end_time, 0.1);
    EXPECT_LT(flown->summary.end_time, 2.0);
  }
}

}  // namespace
}  // namespace thetad
