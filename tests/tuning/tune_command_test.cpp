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
      {tune("--objective entries --entry-floor 2"), "--entry-floor must lie in (0, 1], got 2"},
      {tune("--seed 7 --holdout-seed 5 --holdout-draws 3"), "must not repeat a training draw, and seed 7 is in both"},
      {tune("--max-seconds -1"), "--max-seconds"},
      {tune("--objective speed"), "--objective"},
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
  const Output first = thetad(tune("--record " + path("record.csv") + " --holdout-draws 3"));
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_THAT(first.out, HasSubstr("scenario=climb controller=theta-d parameters=series objective=sigma terms=3 algorithm=LN_BOBYQA "
                                    "record_samples=200 weighting=absolute"));
  EXPECT_THAT(first.out, HasSubstr("validation scenario=climb role=tuning_scenario draws=3 first_seed=8 pairs=3"));
  EXPECT_THAT(first.out, HasSubstr("validation scenario=climb metric=cost default_median="));
  EXPECT_THAT(first.out, HasSubstr("validation scenario=climb metric=rms_error_m default_median="));
  for (const char* file : {"theta-d-tuned.yaml", "sigma-curves.csv", "tuning.json"}) EXPECT_TRUE(fs::exists(dir_ / "out" / file)) << file;
  EXPECT_TRUE(fs::exists(dir_ / "record.csv"));

  const Output run = thetad("run --scenario " + path("climb.yaml") + " --ideal --controller theta-d --settings " +
                            path("out/theta-d-tuned.yaml") + " --out " + path("run"));
  EXPECT_EQ(run.status, 0) << run.err;
  // The settings file is a controller spec's file: default and tuned side by side, and the tuned
  // one flies exactly what the tuner validated on its first held-out draw.
  const Output compare = thetad("compare --scenario " + path("climb.yaml") + " --ideal --seed 8 --controllers paper=theta-d," +
                                "tuned=theta-d:" + path("out/theta-d-tuned.yaml") + " --out " + path("compare"));
  ASSERT_EQ(compare.status, 0) << compare.err;
  const auto tuning = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "tuning.json"));
  const auto tuned = nlohmann::json::parse(thetad::testing::read_text(dir_ / "compare" / "tuned.json"));
  EXPECT_EQ(tuned["controller_settings"]["k"], tuning["k"]);
  EXPECT_EQ(tuned["controller_settings"]["l"], tuning["l"]);
  const auto& validation = tuning["validation"][0];
  EXPECT_EQ(validation["runs"][0]["seed"], 8);
  EXPECT_EQ(tuned["cost"], validation["runs"][0]["tuned"]["cost"]);
  // The report names the objective and its settings; the fit's seed is the scenario's (7), not
  // the command line's default, and the held-out draws start after it.
  EXPECT_EQ(tuning["objective"]["name"], "sigma");
  EXPECT_EQ(tuning["objective"]["weighting"], "absolute");
  EXPECT_EQ(tuning["seed"], 7);
  EXPECT_EQ(validation["role"], "tuning_scenario");
  EXPECT_EQ(validation["bootstrap"]["seed"], 7);
  // The names of docs/glossary.md, format_version 2 (tuning/tuning_report.hpp).
  EXPECT_EQ(tuning["format"], "thetad-tuning-1");
  EXPECT_EQ(tuning["format_version"], 2);
  EXPECT_EQ(tuning["record_samples"], 200);
  EXPECT_EQ(tuning["record_reused"], false);
  EXPECT_EQ(validation["default_not_completed"], 0);
  EXPECT_EQ(validation["tuned_not_completed"], 0);
  EXPECT_EQ(validation["rms_error_m"]["metric"], "rms_error_m");
  EXPECT_EQ(validation["rms_error_m"]["difference_ci95"].size(), 2u);
  EXPECT_EQ(validation["runs"][0]["tuned"]["status"], "completed");
  EXPECT_EQ(validation["runs"][0]["tuned"]["end_time_s"], 2.0);

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

// The other two objectives through the command: the report names each with its settings, and
// the closed loop's held-out draws are not its training draws.
TEST_F(TuneCommand, EntriesAndClosedLoopObjectivesAreReportedWithTheirSettings) {
  const Output entries = thetad(tune("--objective entries --entry-floor 0.01 --holdout-draws 2 --max-evaluations 30"));
  ASSERT_EQ(entries.status, 0) << entries.err;
  EXPECT_THAT(entries.out, HasSubstr("objective=entries terms=3 algorithm=LN_BOBYQA record_samples=200 entry_floor=0.01"));
  EXPECT_THAT(entries.out, HasSubstr("default_rms_relative_entry_error="));
  auto report = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "tuning.json"));
  EXPECT_EQ(report["objective"], (nlohmann::json{{"name", "entries"}, {"entry_floor", 0.01}, {"every", 10}}));
  EXPECT_LE(report["evaluations"].get<int>(), 30);
  EXPECT_LE(report["tuned_objective"].get<double>(), report["default_objective"].get<double>());
  EXPECT_FALSE(fs::exists(dir_ / "out" / "sigma-curves.csv"));

  // Without --ideal the draws differ; one second keeps it short. The metric by its former name,
  // which the command still accepts.
  const std::string closed_loop = "tune --scenario " + path("climb.yaml") + " --duration 1 --out " + path("loop") +
                                  " --objective closed-loop --metric rms-error --draws 2 --holdout-draws 3 "
                                  "--max-evaluations 5";
  const Output loop = thetad(closed_loop);
  ASSERT_EQ(loop.status, 0) << loop.err;
  EXPECT_THAT(loop.out, HasSubstr("controller=theta-d parameters=series objective=closed-loop terms=3 algorithm=LN_COBYLA "
                                  "metric=rms_error_m training_draws=2"));
  EXPECT_THAT(loop.out, HasSubstr("default_mean_rms_error_m="));
  report = nlohmann::json::parse(thetad::testing::read_text(dir_ / "loop" / "tuning.json"));
  EXPECT_EQ(report["objective"]["name"], "closed-loop");
  EXPECT_EQ(report["objective"]["metric"], "rms_error_m");
  EXPECT_EQ(report["objective"]["training_seeds"], (nlohmann::json{7, 8}));
  EXPECT_LE(report["evaluations"].get<int>(), 5);
  EXPECT_EQ(report["budget"]["evaluations"], 5);
  std::vector<std::uint64_t> held_out;
  for (const auto& run : report["validation"][0]["runs"]) held_out.push_back(run["seed"].get<std::uint64_t>());
  EXPECT_EQ(held_out, (std::vector<std::uint64_t>{9, 10, 11}));

  // Another controller's weights, the same objective and budget: the SDRE's settings file flies.
  const Output weights = thetad("tune --scenario " + path("climb.yaml") + " --duration 1 --out " + path("weights") +
                                " --controller sdre --objective closed-loop --metric cost-dev --draws 1 --holdout-draws 2 "
                                "--max-evaluations 3 --weight-bounds 1");
  ASSERT_EQ(weights.status, 0) << weights.err;
  EXPECT_THAT(weights.out, HasSubstr("controller=sdre parameters=weights objective=closed-loop"));
  EXPECT_THAT(weights.out, HasSubstr("log10 R[T_mr]="));
  EXPECT_THAT(weights.out, HasSubstr("metric=cost_dev default_median="));
  report = nlohmann::json::parse(thetad::testing::read_text(dir_ / "weights" / "tuning.json"));
  EXPECT_EQ(report["controller"], "sdre");
  EXPECT_EQ(report["parameters"]["kind"], "weights");
  EXPECT_EQ(report["parameters"]["names"].size(), 9u);
  EXPECT_EQ(report["parameters"]["upper"][0], 1.0);
  EXPECT_LE(report["tuned_objective"].get<double>(), report["default_objective"].get<double>());
  EXPECT_TRUE(report["validation"][0].contains("cost_dev"));
  const Output run = thetad("run --scenario " + path("climb.yaml") + " --duration 0.2 --controller sdre --settings " +
                            path("weights/sdre-tuned.yaml") + " --out " + path("weights-run"));
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(thetad(tune("--controller lqr --parameters series")).err, HasSubstr("only theta-d has a series"));
  EXPECT_THAT(thetad(tune("--controller lqr")).err, HasSubstr("tuned by the closed loop only"));
}

// thetad approximation: bad input is one line and nothing written; a short flight writes the CSV
// and the JSON with the quantiles and the provenance.
TEST_F(TuneCommand, ApproximationWritesItsErrorsWithProvenance) {
  const Output bad = thetad("approximation --scenario " + path("missing.yaml") + " --out " + path("approx"));
  EXPECT_EQ(bad.status, 1);
  EXPECT_THAT(bad.err, StartsWith("thetad: error: "));
  EXPECT_FALSE(fs::exists(dir_ / "approx"));

  const Output run = thetad("approximation --scenario " + path("climb.yaml") + " --duration 0.5 --out " + path("approx"));
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("scenario=climb duration_s=0.5 seed=7 samples=50"));
  EXPECT_THAT(run.out, HasSubstr("control_relative median="));
  const std::string csv = thetad::testing::read_text(dir_ / "approx" / "approximation.csv");
  EXPECT_THAT(csv, StartsWith("t_s,frobenius_relative,sigma_relative,control_relative,u_sdre_0,"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 51);
  const auto json = nlohmann::json::parse(thetad::testing::read_text(dir_ / "approx" / "approximation.json"));
  EXPECT_EQ(json["errors"]["samples"], 50);
  for (const char* name : {"frobenius", "sigma", "control"})
    EXPECT_LE(json["errors"][name]["median"].get<double>(), json["errors"][name]["max"].get<double>()) << name;
  EXPECT_EQ(json["theta_d_settings"]["terms"], 3);
  EXPECT_EQ(json["provenance"]["scenario"]["name"], "climb");
  EXPECT_EQ(json["provenance"]["scenario"]["sha256"].get<std::string>().size(), 64u);
}

}  // namespace
