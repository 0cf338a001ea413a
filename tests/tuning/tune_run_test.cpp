// tuning::tune, the run every front end calls: the files it writes are its report, its tasks reach
// a Progress listener in order, and a run stopped by its observer on the way writes no result file.

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/scratch_directory.hpp"
#include "tuning/tune_run.hpp"

namespace thetad::tuning {
namespace {

namespace fs = std::filesystem;

// The closed loop on one second of scenario I: one training and one held-out draw, two evaluations.
TuneOptions one_second(const fs::path& out) {
  TuneOptions options;
  options.scenario = THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml";
  options.controls.duration = 1.0;
  options.controls.timing = false;
  options.out = out;
  options.objective = "closed-loop";
  options.draws = 1;
  options.holdout_draws = 1;
  options.max_evaluations = 2;
  return options;
}

TEST(TuneRun, WritesItsReportAndReportsItsTasks) {
  const testing::ScratchDirectory scratch("thetad_tune_run_test");
  std::vector<std::string> started;
  Progress progress(Progress::Mode::quiet, [&](const ProgressEvent& event) {
    if (event.done == 0.0) started.push_back(event.label);
  });
  const TuningReport report = tune(one_second(scratch.path()), &progress);
  EXPECT_EQ(started, (std::vector<std::string>{"fit (closed-loop, LN_COBYLA):", "validation on scenario-1:",
                                               "validation on scenario-2:"}));
  ASSERT_EQ(report.files.size(), 2u);
  EXPECT_EQ(report.files[0], scratch.path() / "theta-d-tuned.yaml");
  EXPECT_EQ(nlohmann::ordered_json::parse(std::ifstream(report.files[1])), to_json(report));
  EXPECT_EQ(report.fit.evaluations, 2);
  EXPECT_EQ(report.validations.size(), 2u);
  // Scenarios I and II take off alike: over one second the held-out one is no other scenario.
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("the held-out scenario scenario-2 commands the same motion as scenario-1"),
            std::string::npos);
}

TEST(TuneRun, AStoppedRunWritesNoResultFile) {
  const testing::ScratchDirectory scratch("thetad_tune_run_test");
  struct Stop {};
  bool validating = false;
  Progress progress(Progress::Mode::quiet, [&](const ProgressEvent& event) {
    validating = validating || event.label.rfind("validation", 0) == 0;
  });
  // Stopped in the validation's flights, after the search: the tuned settings are known by then.
  EXPECT_THROW(tune(one_second(scratch.path()), &progress,
                    [&](double) {
                      if (validating) throw Stop{};
                    }),
               Stop);
  EXPECT_TRUE(validating);
  EXPECT_TRUE(fs::is_empty(scratch.path()));
}

}  // namespace
}  // namespace thetad::tuning
