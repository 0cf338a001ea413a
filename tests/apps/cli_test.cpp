// Runs the built thetad program (THETAD_BINARY) the way a user does.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "settings/run_settings.hpp"
#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

using thetad::testing::Output;
std::string read(const fs::path& file) { return thetad::testing::read_text(file); }

void write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    // A 2 s hold on the ground: the shortest flight that exercises every step of a run.
    write(dir_ / "hover.yaml", "name: tiny\nduration: 2\nphases:\n  - name: hover\n    type: hold\n    time: [0, 2]\n");
  }
  // thetad with `arguments` (a shell command line tail), CI set so progress comes as plain lines.
  Output thetad(const std::string& arguments) const { return thetad::testing::run_thetad(dir_, arguments); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  thetad::testing::ScratchDirectory scratch_{"thetad_cli_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(Cli, ListShowsTheRegisteredControllers) {
  const Output output = thetad("list");
  EXPECT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("lqr "));
  EXPECT_THAT(output.out, HasSubstr("example-pid "));
}

// Every run setting with an option of its own (settings/run_settings.hpp) is an option of the
// commands that fly; those about run files only of the commands that write them.
TEST_F(Cli, EveryRunSettingWithAnOptionIsOffered) {
  const Output run = thetad("run --help");
  const Output bench = thetad("bench --help");
  ASSERT_EQ(run.status, 0) << run.err;
  ASSERT_EQ(bench.status, 0) << bench.err;
  for (const thetad::RunSetting& setting : thetad::run_settings()) {
    if (setting.option.empty()) continue;
    const std::string option = std::string(setting.option) + " ";
    EXPECT_THAT(run.out, HasSubstr(option));
    if (setting.option_writes_runs) {
      EXPECT_THAT(bench.out, Not(HasSubstr(option)));
    } else {
      EXPECT_THAT(bench.out, HasSubstr(option));
    }
  }
}

TEST_F(Cli, RunWritesTheLogAndAParsableSummary) {
  const Output output = thetad("run --scenario " + path("hover.yaml") + " --controller lqr --ideal --out " + path("out"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("lqr on tiny (2 s, seed 1, ideal"));
  EXPECT_THAT(output.out, HasSubstr("completed"));
  EXPECT_THAT(output.err, HasSubstr("lqr: flying (2 s simulated)"));
  ASSERT_TRUE(fs::exists(dir_ / "out" / "lqr.csv"));
  const nlohmann::json summary = nlohmann::json::parse(read(dir_ / "out" / "lqr.json"));
  EXPECT_EQ(summary["controller"], "lqr");
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_EQ(summary["controller_samples"], 2000);
  EXPECT_EQ(summary["settings"]["wind_gust"]["enabled"], false);
}

TEST_F(Cli, CompareFliesEachControllerAndPrintsTheTable) {
  const Output output = thetad("compare --scenario " + path("hover.yaml") + " --controllers lqr,example-pid --seed 3 --out " +
                               path("out"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("tiny (2 s, seed 3, all disturbances"));
  EXPECT_THAT(output.out, HasSubstr("controller"));
  EXPECT_THAT(output.out, HasSubstr("RMS tracking error (m)"));
  EXPECT_THAT(output.out, HasSubstr("3-D"));
  EXPECT_THAT(output.out, HasSubstr("\nlqr "));
  EXPECT_THAT(output.out, HasSubstr("\nexample-pid "));
  EXPECT_THAT(output.err, HasSubstr("[1/2] lqr:"));
  EXPECT_THAT(output.err, HasSubstr("[2/2] example-pid:"));
  const nlohmann::json comparison = nlohmann::json::parse(read(dir_ / "out" / "comparison.json"));
  EXPECT_EQ(comparison["seed"], 3);
  ASSERT_EQ(comparison["runs"].size(), 2u);
  EXPECT_EQ(comparison["runs"][1]["controller"], "example-pid");
  const nlohmann::json first = nlohmann::json::parse(read(dir_ / "out" / comparison["runs"][0]["json"].get<std::string>()));
  const nlohmann::json second = nlohmann::json::parse(read(dir_ / "out" / comparison["runs"][1]["json"].get<std::string>()));
  EXPECT_EQ(second["seed"], 3);
  // The same seed: the same perturbed plant for both controllers.
  EXPECT_EQ(first["parameter_factors"], second["parameter_factors"]);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "example-pid.csv"));
}

TEST_F(Cli, ABadScenarioFieldIsOneLineWithFileLineAndFieldAndWritesNothing) {
  write(dir_ / "bad.yaml",
        "duration: 50\nphases:\n  - name: eight\n    type: figure8\n    time: [0, 50]\n    amplitude_x: 8\n"
        "    amplitude_y: 4\n    period: 0\n");
  const Output output = thetad("compare --scenario " + path("bad.yaml") + " --controllers lqr,example-pid --out " + path("out"));
  EXPECT_NE(output.status, 0);
  EXPECT_EQ(output.err, "thetad: error: " + path("bad.yaml") + ":8:13: field 'phases.eight.period': must be > 0\n");
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(Cli, ABadSettingsFileNamesFileLineAndFieldAndWritesNothing) {
  write(dir_ / "settings.yaml", "lqr:\n  R: [1, 200, 1e7, 1e5]\n");
  Output output = thetad("run --scenario " + path("hover.yaml") + " --controller lqr --settings " + path("settings.yaml") +
                         " --out " + path("out"));
  EXPECT_NE(output.status, 0);
  EXPECT_THAT(output.err, HasSubstr(path("settings.yaml") + ":2:6: field 'R': expected 5 entries, got 4"));
  EXPECT_FALSE(fs::exists(dir_ / "out"));

  write(dir_ / "settings.yaml", "lqr: {}\nthetad: {}\n");
  output = thetad("run --scenario " + path("hover.yaml") + " --controller lqr --settings " + path("settings.yaml") +
                  " --out " + path("out"));
  EXPECT_NE(output.status, 0);
  EXPECT_THAT(output.err, HasSubstr(path("settings.yaml") + ":2:1: field 'thetad': unknown controller (known: "));
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(Cli, DesignLqrWritesATableThatTheScheduledControllerFlies) {
  write(dir_ / "grid.yaml", "speeds: [0, 2]\ncourses_deg: [0]\nclimb_rates: [0]\n");
  Output output = thetad("design-lqr --grid " + path("grid.yaml") + " --out " + path("table.json"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("2 grid points (2 speeds x 1 courses x 1 climb rates), 0 with the governor"));
  // CI is set: one plain progress line per point, no terminal control codes.
  EXPECT_THAT(output.err, HasSubstr("[1/2] speed  0.00 m/s"));
  EXPECT_THAT(output.err, HasSubstr("[2/2] speed  2.00 m/s"));
  EXPECT_THAT(output.err, Not(HasSubstr("\033")));
  const auto table = nlohmann::json::parse(read(dir_ / "table.json"));
  EXPECT_EQ(table["grid"]["speeds"], nlohmann::json::array({0.0, 2.0}));
  EXPECT_EQ(table["points"].size(), 2u);

  write(dir_ / "settings.yaml", "lqr-scheduled:\n  table: " + path("table.json") + "\n");
  output = thetad("run --scenario " + path("hover.yaml") + " --controller lqr-scheduled --settings " +
                  path("settings.yaml") + " --ideal --out " + path("out"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("completed"));
}

TEST_F(Cli, DesignLqrRejectsABadGridWithFileAndFieldAndWritesNothing) {
  write(dir_ / "grid.yaml", "speeds: [2, 0]\ncourses_deg: [0]\nclimb_rates: [0]\n");
  Output output = thetad("design-lqr --grid " + path("grid.yaml") + " --out " + path("table.json"));
  EXPECT_NE(output.status, 0);
  EXPECT_THAT(output.err, HasSubstr(path("grid.yaml") + ":1:"));
  EXPECT_THAT(output.err, HasSubstr("field 'speeds'"));
  EXPECT_FALSE(fs::exists(dir_ / "table.json"));

  write(dir_ / "grid.yaml", "speeds: [0]\nheadings: [0]\n");
  output = thetad("design-lqr --grid " + path("grid.yaml") + " --out " + path("table.json"));
  EXPECT_NE(output.status, 0);
  EXPECT_THAT(output.err, HasSubstr("field 'headings'"));
  EXPECT_FALSE(fs::exists(dir_ / "table.json"));
}

TEST_F(Cli, BadArgumentsAreOneLine) {
  Output output = thetad("compare --scenario " + path("hover.yaml") + " --controllers lqr,nonesuch --out " + path("out"));
  EXPECT_NE(output.status, 0);
  EXPECT_THAT(output.err, HasSubstr("unknown controller 'nonesuch'"));
  EXPECT_FALSE(fs::exists(dir_ / "out"));

  output = thetad("run --scenario " + path("missing.yaml") + " --controller lqr --out " + path("out"));
  EXPECT_NE(output.status, 0);
  EXPECT_EQ(output.err, "thetad: error: scenario '" + path("missing.yaml") + "': no such file\n");

  output = thetad("run --scenario " + path("hover.yaml") + " --out " + path("out"));
  EXPECT_NE(output.status, 0);
  EXPECT_EQ(output.err, "thetad: error: thetad run needs --scenario, --controller and --out (or --replay RESULT.json)\n");
  EXPECT_THAT(output.out, Not(HasSubstr("Usage")));
}

// The small traps of a first hour: a scenario name that is not shipped lists those that are; a
// mistyped option gets the nearest one; a shipped campaign is named like a shipped scenario.
TEST_F(Cli, NamesAndOptionsThatAreNearlyRightSayWhatIsThere) {
  Output output = thetad("run --scenario scenario-3 --controller lqr --out " + path("out"));
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("scenario 'scenario-3': no such file, nor a shipped scenario of that name "
                                    "(shipped: fast-forward, hover-hold, hover-step, hover-to-hover, scenario-1, "
                                    "scenario-2; looked in "));
  output = thetad("run --scenaro scenario-1 --controller lqr --out " + path("out"));
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("(did you mean --scenario?)"));
  output = thetad("compare --scenario scenario-1 --controlers lqr --out " + path("out"));
  EXPECT_THAT(output.err, HasSubstr("(did you mean --controllers?)"));
  output = thetad("run --frobnicate --out " + path("out"));
  EXPECT_THAT(output.err, Not(HasSubstr("did you mean")));
  output = thetad("campaign run fair/legs-20 --dry-run --pilot 0.01");
  EXPECT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("fair-legs-20: 1 scenario(s) x 24 controller(s) x 2 cell(s) x 5 draws = 240 runs"));
  output = thetad("campaign run scenario-1-paired-fsat --dry-run");
  EXPECT_THAT(output.err, HasSubstr("campaign 'scenario-1-paired-fsat': no such file, nor a shipped campaign of that "
                                    "name (shipped: envelope, envelope-quick, envelope-sdre, envelope-wide, "
                                    "scenario-1-paired, scenario-1-paired-fast, scenario-1-paired-sdre; looked in "));
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

}  // namespace
