// "A controller is one file": a controller registered by a plug-in and named nowhere else (tests/
// plugins/test_only_controller_plugin.cpp) reaches every front end of the program: list, run,
// compare (also through "all", the registry's list), bench (with the iterations it reports) and a
// campaign. tests python/tests/test_plugins.py does the same from Python.

#include <filesystem>
#include <fstream>
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

class OneFileController : public ::testing::Test {
 protected:
  Output thetad(const std::string& arguments) const {
    return thetad::testing::run_thetad(dir_, std::string("--plugin ") + THETAD_TEST_ONLY_PLUGIN + " " + arguments);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  nlohmann::json json(const std::string& name) const {
    return nlohmann::json::parse(thetad::testing::read_text(dir_ / name));
  }

  thetad::testing::ScratchDirectory scratch_{"thetad_one_file_controller_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(OneFileController, IsListedAndFlies) {
  Output output = thetad("list");
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("\ntest-only "));
  output = thetad("run --scenario hover-to-hover --controller test-only --duration 0.3 --out " + path("run"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_EQ(json("run/test-only.json")["controller"], "test-only");
  // Its own log column, a plain one (not a certificate), before the step time: 300 samples at 1 kHz.
  const std::string csv = thetad::testing::read_text(dir_ / "run" / "test-only.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_THAT(header, ::testing::EndsWith(",steps,in_flight_step_time_ns"));
  const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  EXPECT_THAT(last, HasSubstr(",300,"));
  EXPECT_FALSE(json("run/test-only.json").contains("certificates"));
}

TEST_F(OneFileController, IsComparedByNameAndAmongAll) {
  const Output output = thetad("compare --scenario hover-to-hover --controllers all --duration 0.3 --no-timing --out " +
                               path("compare"));
  ASSERT_EQ(output.status, 0) << output.err;
  const nlohmann::json comparison = json("compare/comparison.json");
  std::vector<std::string> flown;
  for (const auto& run : comparison["runs"]) flown.push_back(run["controller"]);
  EXPECT_THAT(flown, ::testing::Contains("test-only"));
  EXPECT_THAT(flown, ::testing::Contains("theta-d"));
  EXPECT_THAT(flown, ::testing::Not(::testing::Contains("example-pid")));  // examples are not compared
}

TEST_F(OneFileController, IsBenchedWithTheIterationsItReports) {
  const Output output = thetad("bench --scenario hover-to-hover --duration 0.5 --controllers theta-d,test-only,lqr"
                               " --samples 20 --segments 1 --repetitions 1 --warmup 0 --out " + path("bench.json"));
  ASSERT_EQ(output.status, 0) << output.err;
  const auto rows = json("bench.json")["controllers"];
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1]["label"], "test-only");
  EXPECT_EQ(rows[1]["iterations_mean"], 2.0);
  EXPECT_GE(rows[0]["iterations_mean"].get<double>(), 1.0);  // θ–D's fixed-point passes
  EXPECT_EQ(rows[2]["iterations_mean"], 0.0);                // the LQR is closed form
}

TEST_F(OneFileController, FliesInACampaign) {
  std::ofstream(dir_ / "campaign.yaml") << "campaign: one-file\nscenarios: [hover-to-hover]\ncontrollers:\n"
                                           "  - {controller: test-only}\n  - {controller: lqr}\n"
                                           "draws: {count: 2, base_seed: 1}\nfixed: {duration: 0.3}\n";
  const Output output = thetad("campaign run " + path("campaign.yaml") + " --out " + path("campaign") +
                               " --jobs 1 --no-timing --quiet");
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("4 runs"));
}

}  // namespace
