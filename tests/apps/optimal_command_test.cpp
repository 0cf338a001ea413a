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
  EXPECT_THAT(output.out, HasSubstr("hover-to-hover, 0.2 s from t = 0 s"));
  // The cheapest flight is the warm start.
  EXPECT_THAT(output.out, HasSubstr("optimal: Ipopt Solve_Succeeded"));
  EXPECT_THAT(output.out, HasSubstr("from sdre's flight; input held 0.05 s (4 intervals)"));
  const nlohmann::json result = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "optimality.json"));
  EXPECT_EQ(result["format"], "thetad-optimality-2");
  ASSERT_EQ(result["optima"].size(), 1u);
  EXPECT_TRUE(result["optima"][0]["ipopt_converged"].get<bool>());
  const double optimal_cost = result["optima"][0]["optimal_cost"].get<double>();
  ASSERT_EQ(result["controllers"].size(), 2u);
  for (const auto& controller : result["controllers"]) {
    EXPECT_GE(controller["gap_percent"].get<double>(), 0.0) << controller["label"];
    EXPECT_EQ(controller["optimal_cost"].get<double>(), optimal_cost);
    EXPECT_NEAR(controller["cost"].get<double>(), optimal_cost * (1.0 + controller["gap_percent"].get<double>() / 100.0),
                1e-9 * controller["cost"].get<double>());
  }
  // The optimum is a run of the comparison, as `thetad plot` reads one.
  const nlohmann::json optimum = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "optimal.json"));
  EXPECT_EQ(optimum["label"], "optimal");
  EXPECT_EQ(optimum["cost"]["J"].get<double>(), optimal_cost);
  EXPECT_EQ(optimum["log"]["rows"], 200);
  const nlohmann::json comparison = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "comparison.json"));
  EXPECT_EQ(comparison["runs"].size(), 3u);
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
