// thetad optimal as a user runs it: a short horizon writes the gap table, the optimum beside the
// flights and optimality.json; bad arguments stop it with one clear line before anything flies.

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using thetad::testing::Output;

class OptimalCommand : public ::testing::Test {
 protected:
  Output thetad(const std::string& arguments) const { return thetad::testing::run_thetad(dir_, arguments); }
  std::string out() const { return (dir_ / "out").string(); }

  thetad::testing::ScratchDirectory scratch_{"thetad_optimal_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(OptimalCommand, PrintsEachGapAndWritesTheOptimumBesideTheFlights) {
  const Output output = thetad("optimal --scenario hover-to-hover --horizon 0.2 --controllers lqr,sdre --no-timing --out " + out());
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("hover-to-hover, 0.2 s from t = 0 s (ideal; J_dev of every controller sample"));
  EXPECT_THAT(output.out, HasSubstr("optimal: Ipopt Solve_Succeeded"));
  EXPECT_THAT(output.out, HasSubstr("input held 0.05 s (4 intervals)"));
  const nlohmann::json result = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "optimality.json"));
  EXPECT_EQ(result["format"], "thetad-optimality-3");
  EXPECT_EQ(result["format_version"], 2);
  EXPECT_EQ(result["cost"]["name"], "J_dev");
  EXPECT_THAT(result["cost"]["weights"].get<std::string>(), HasSubstr("designed weights"));
  EXPECT_EQ(result["input_bounds"], "none");
  EXPECT_TRUE(result["converged"].get<bool>());
  EXPECT_TRUE(result["unbounded_at_most_bounded"].is_null());
  ASSERT_EQ(result["optima"].size(), 1u);
  EXPECT_FALSE(result["optima"][0].contains("unbounded"));
  const nlohmann::json& solve = result["optima"][0]["optimum"];
  EXPECT_TRUE(solve["ipopt_converged"].get<bool>());
  const double optimal_cost = solve["cost_dev"].get<double>();
  ASSERT_EQ(result["controllers"].size(), 2u);
  for (const auto& controller : result["controllers"]) {
    EXPECT_GE(controller["gap_percent"].get<double>(), 0.0) << controller["label"];
    EXPECT_EQ(controller["status"], "completed") << controller["label"];
    EXPECT_EQ(controller["end_time_s"].get<double>(), 0.2) << controller["label"];
    EXPECT_EQ(controller["optimal_cost"].get<double>(), optimal_cost);
    EXPECT_NEAR(controller["cost"].get<double>(), optimal_cost * (1.0 + controller["gap_percent"].get<double>() / 100.0),
                1e-9 * controller["cost"].get<double>());
  }
  // The optimum is a run of the comparison, as `thetad plot` reads one, scored as the flights are.
  const nlohmann::json optimum = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "optimal.json"));
  EXPECT_EQ(optimum["label"], "optimal");
  EXPECT_EQ(optimum["cost_dev"].get<double>(), optimal_cost);
  EXPECT_EQ(optimum["cost"].get<double>(), solve["cost"].get<double>());
  EXPECT_EQ(optimum["log"]["rows"], 200);
  const nlohmann::json comparison = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "comparison.json"));
  EXPECT_EQ(comparison["runs"].size(), 3u);
}

// With the actuator limits the optimum is solved bounded, then unbounded from it; on J too.
TEST_F(OptimalCommand, WithLimitsSolvesBoundedThenUnbounded) {
  const Output output = thetad("optimal --scenario hover-step --horizon 0.2 --controllers lqr --cost j "
                               "--actuator-limits on --no-timing --out " + out());
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("(ideal, actuator limits; the optimum bounded by their magnitudes; J of every"));
  EXPECT_THAT(output.out, HasSubstr("optimal-unbounded: Ipopt Solve_Succeeded"));
  const nlohmann::json result = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "optimality.json"));
  EXPECT_EQ(result["cost"]["name"], "J");
  EXPECT_THAT(result["input_bounds"].get<std::string>(), HasSubstr("magnitude limits"));
  EXPECT_TRUE(result["unbounded_at_most_bounded"].get<bool>());
  const nlohmann::json& optimum = result["optima"][0];
  EXPECT_EQ(optimum["unbounded"]["label"], "optimal-unbounded");
  EXPECT_GE(optimum["bounded_minus_unbounded"].get<double>(), -1e-6 * optimum["optimum"]["cost"].get<double>());
  const nlohmann::json& lqr = result["controllers"][0];
  EXPECT_EQ(lqr["unbounded_optimal_cost"].get<double>(), optimum["unbounded"]["cost"].get<double>());
  EXPECT_TRUE(fs::exists(dir_ / "out" / "optimal-unbounded.json"));
  const nlohmann::json flown = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "lqr.json"));
  EXPECT_TRUE(flown["settings"]["actuator_limits"]["enabled"].get<bool>());
}

TEST_F(OptimalCommand, FromMidFlightSolvesFromEachControllersState) {
  const Output output =
      thetad("optimal --scenario hover-to-hover --start 0.1 --horizon 0.1 --controllers lqr --no-timing --out " + out());
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("hover-to-hover, 0.1 s from t = 0.1 s"));
  EXPECT_THAT(output.out, HasSubstr("optimal-from-lqr: Ipopt Solve_Succeeded"));
  const nlohmann::json result = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "optimality.json"));
  EXPECT_EQ(result["start_s"].get<double>(), 0.1);
  EXPECT_EQ(result["controllers"][0]["optimum"], "optimal-from-lqr");
  EXPECT_GE(result["controllers"][0]["gap_percent"].get<double>(), 0.0);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "optimal-from-lqr.csv"));
}

TEST_F(OptimalCommand, BadArgumentsAreOneClearLine) {
  // One controller: every refusal comes before (or instead of) flying it.
  Output output = thetad("optimal --scenario hover-to-hover --horizon 0.2 --control-interval 0.0305 --controllers lqr --out " + out());
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("thetad: error: optimality gap: the control interval (0.030500 s) is not a whole "
                                    "number of controller periods (0.001000 s)"));
  output = thetad("optimal --scenario hover-to-hover --horizon 0.22 --controllers lqr --out " + out());
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("the horizon (0.220000 s) is not a whole number of control intervals (0.050000 s)"));
  output = thetad("optimal --scenario hover-to-hover --horizon -1 --controllers lqr --out " + out());
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("--horizon"));
  output = thetad("optimal --scenario hover-to-hover --horizon 0.2 --controllers lqr --warm-start sdre --out " + out());
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("the warm start sdre is none of the controllers flown"));
  output = thetad("optimal --scenario hover-to-hover --horizon 0.2 --controllers optimal=lqr --out " + out());
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("labels starting 'optimal' name the optima"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "optimality.json"));
}

}  // namespace
