// thetad tune as a user runs it: bad input fails with one line and writes nothing; a small tuning
// writes a settings file that thetad run accepts, and a reused record gives the same fit.

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

using thetad::testing::Output;

class TuneCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    // Two seconds of a slow climb: the smallest flight with a trajectory to tune on.
    std::ofstream(dir_ / "climb.yaml") << "name: climb\nduration: 2\nphases:\n  - name: up\n    type: ramp\n"
                                          "    time: [0, 2]\n    to: [0, 0, 1]\nsimulation:\n  seed: 7\n";
  }
  Output thetad(const std::string& arguments) const { return thetad::testing::run_thetad(dir_, arguments); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string tune(const std::string& extra) const {
    return "tune --scenario " + path("climb.yaml") + " --ideal --out " + path("out") + " " + extra;
  }

  thetad::testing::ScratchDirectory scratch_{"thetad_tune_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(TuneCommand, BadInputFailsWithOneLineAndWritesNothing) {
  const std::string head = "# thetad tuning record v1: SDRE flight, sigma_max of P_SDRE at each kept sample\n"
                           "# scenario: climb\n";
  std::string columns = "t_s";
  for (int i = 0; i < 18; ++i) columns += ",x_" + std::to_string(i);
  for (int i = 0; i < 5; ++i) columns += ",u_" + std::to_string(i);
  columns += ",sigma_max_P\n";
  std::string row = "0";
  for (int i = 0; i < 24; ++i) row += i == 3 ? ",nan" : ",1";
  std::ofstream(dir_ / "nan.csv") << head << columns << row << "\n";
  std::ofstream(dir_ / "columns.csv") << head << "t_s,x_0,sigma_max_P\n0,1,2\n";
  std::string valid = "0";
  for (int i = 0; i < 24; ++i) valid += ",1";
  std::ofstream(dir_ / "other.csv") << head.substr(0, head.find("# scenario")) << "# scenario: scenario-2\n" << columns
                                    << valid << "\n";
  const struct {
    std::string arguments, message;
  } cases[] = {
      {tune("--algorithm LN_MAGIC"), "unknown algorithm 'LN_MAGIC'"},
      {tune("--k-bounds 1.5 0"), "the bounds of k are reversed"},
      {tune("--record " + path("nan.csv")), "nan.csv:4: column 5: not finite"},
      {tune("--record " + path("columns.csv")), "columns.csv:3: wrong columns"},
      {tune("--record " + path("other.csv")), "recorded on scenario 'scenario-2', not 'climb'"},
      {tune("--holdout " + path("missing.yaml")), "missing.yaml"},
      {"tune --scenario " + path("missing.yaml") + " --out " + path("out"), "missing.yaml"},
  };
  for (const auto& c : cases) {
    const Output output = thetad(c.arguments);
    EXPECT_EQ(output.status, 1) << c.arguments;
    EXPECT_THAT(output.err, StartsWith("thetad: error: ")) << c.arguments;
    EXPECT_THAT(output.err, HasSubstr(c.message)) << c.arguments;
    EXPECT_EQ(std::count(output.err.begin(), output.err.end(), '\n'), 1) << output.err;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << c.arguments;
  }
}

TEST_F(TuneCommand, WritesASettingsFileThatRunAcceptsAndReusesItsRecord) {
  const Output first = thetad(tune("--record " + path("record.csv")));
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_THAT(first.out, HasSubstr("scenario=climb samples=200 terms=3 algorithm=LN_BOBYQA"));
  EXPECT_THAT(first.out, HasSubstr("validation scenario=climb role=tuning theta_d=tuned status=\"completed\""));
  for (const char* file : {"theta-d-tuned.yaml", "sigma-curves.csv", "tuning.json"}) EXPECT_TRUE(fs::exists(dir_ / "out" / file)) << file;
  EXPECT_TRUE(fs::exists(dir_ / "record.csv"));

  const Output run = thetad("run --scenario " + path("climb.yaml") + " --ideal --controller theta-d --settings " +
                            path("out/theta-d-tuned.yaml") + " --out " + path("run"));
  EXPECT_EQ(run.status, 0) << run.err;
  // The settings file is a controller spec's file: default and tuned side by side, and the tuned
  // one flies exactly what the tuner validated.
  const Output compare = thetad("compare --scenario " + path("climb.yaml") + " --ideal --controllers paper=theta-d," +
                                "tuned=theta-d:" + path("out/theta-d-tuned.yaml") + " --out " + path("compare"));
  ASSERT_EQ(compare.status, 0) << compare.err;
  const auto tuning = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "tuning.json"));
  const auto tuned = nlohmann::json::parse(thetad::testing::read_text(dir_ / "compare" / "tuned.json"));
  EXPECT_EQ(tuned["controller_settings"]["k"], tuning["k"]);
  EXPECT_EQ(tuned["controller_settings"]["l"], tuning["l"]);
  EXPECT_EQ(tuned["cost"]["J"], tuning["validation"][1]["cost"]);
  EXPECT_EQ(tuning["validation"][1]["parameters"], "tuned");
  // The fit's seed is the scenario's (7), not the command line's default.
  EXPECT_EQ(tuning["seed"], 7);

  // Reusing the record skips the flight and gives the same fit, bit for bit.
  const Output second = thetad(tune("--record " + path("record.csv") + " --no-validation"));
  ASSERT_EQ(second.status, 0) << second.err;
  EXPECT_THAT(second.err, Not(HasSubstr("sdre (record)")));
  const auto line = [](const std::string& text, const std::string& key) {
    const auto begin = text.find("\n" + key);
    return text.substr(begin, text.find('\n', begin + 1) - begin);
  };
  EXPECT_EQ(line(second.out, "k="), line(first.out, "k="));
  EXPECT_EQ(line(second.out, "l="), line(first.out, "l="));
}

}  // namespace
