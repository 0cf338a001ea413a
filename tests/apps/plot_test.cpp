// thetad plot on the output of a short `thetad compare`, run as a user runs them (THETAD_BINARY).

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "experiment/sha256.hpp"
#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

using thetad::testing::Output;
using thetad::testing::read_text;

using thetad::testing::write_text;

void replace_once(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = read_text(file);
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " not in " << file;
  write_text(file, text.replace(at, from.size(), to));
}

Output thetad(const fs::path& directory, const std::string& arguments, const std::string& environment = "") {
  return thetad::testing::run_thetad(directory, arguments, environment);
}

// Every figure the plot command draws: the paper's kinds (Figs. 2-9 / 10-17) and the comparisons.
const std::vector<std::string> kFigures = {
    "trajectory_3d",   "position",        "euler_angles",        "angular_rates",
    "body_velocities", "flapping_angles", "control_deflections", "main_rotor_thrust",
    "tracking_error",  "compute_time",    "summary"};

class Plot : public ::testing::Test {
 protected:
  // One short comparison for every test (the flights are the slow part): a 2 s climb to 0.5 m with
  // two cheap controllers.
  static void SetUpTestSuite() {
    scratch_.emplace("thetad_plot_test");
    root_ = scratch_->path();
    write_text(root_ / "climb.yaml",
          "name: climb\nduration: 2\nphases:\n  - name: climb\n    type: ramp\n    time: [0, 2]\n    to: [0, 0, 0.5]\n");
    compare_ = thetad(root_, "compare --scenario " + (root_ / "climb.yaml").string() +
                                 " --controllers lqr,example-pid --seed 1 --out " + (root_ / "runs").string());
  }
  static void TearDownTestSuite() { scratch_.reset(); }

  void SetUp() override {
    ASSERT_EQ(compare_.status, 0) << compare_.err;
    dir_ = root_ / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir_);
    fs::copy(root_ / "runs", dir_ / "runs");
  }

  Output plot(const std::string& extra = "", const std::string& environment = "") const {
    return thetad(dir_, "plot --in " + (dir_ / "runs").string() + " --out " + (dir_ / "figures").string() + " " + extra,
                  environment);
  }

  // The plot fails with `message` on stderr and writes nothing.
  void expect_rejected(const std::string& message) const {
    const Output output = plot();
    EXPECT_EQ(output.status, 1);
    EXPECT_THAT(output.err, HasSubstr(message));
    expect_nothing_written();
  }

  // A failed plot leaves neither the output directory nor its staging sibling behind.
  void expect_nothing_written() const {
    EXPECT_FALSE(fs::exists(dir_ / "figures"));
    for (const auto& entry : fs::directory_iterator(dir_)) {
      EXPECT_EQ(entry.path().filename().string().find(".figures"), std::string::npos) << entry.path();
    }
  }

  static inline std::optional<thetad::testing::ScratchDirectory> scratch_;
  static inline fs::path root_;
  static inline Output compare_;
  fs::path dir_;
};

TEST_F(Plot, DrawsEveryFigureAsValidPngAndSvg) {
  const Output output = plot();
  ASSERT_EQ(output.status, 0) << output.err;
  // Two formats: the second once printed matplotlib's layout warning (the 3-D figure).
  EXPECT_THAT(output.err, Not(HasSubstr("Warning"))) << output.err;
  for (const auto& figure : kFigures) {
    const std::string png = read_text(dir_ / "figures" / (figure + ".png"));
    const std::string svg = read_text(dir_ / "figures" / (figure + ".svg"));
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << figure;
    EXPECT_GT(png.size(), 1000u) << figure;
    EXPECT_EQ(svg.substr(0, 5), "<?xml") << figure;
    EXPECT_THAT(svg.substr(0, 1000), HasSubstr("<svg")) << figure;
    EXPECT_THAT(output.out, HasSubstr(figure + ".png"));
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "figures"), fs::directory_iterator()), 2 * kFigures.size());
  // The staging directory is gone.
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find(".figures"), std::string::npos) << entry.path();
  }
}

// Labels name the lines, and runs flown without timing (no step-time column) still draw every figure.
TEST_F(Plot, LabelledRunsWithoutTimingDrawEveryFigure) {
  const Output compare = thetad(dir_, "compare --scenario " + (root_ / "climb.yaml").string() +
                                          " --controllers hover=lqr,pid=example-pid --no-timing --log-every 5 --out " +
                                          (dir_ / "untimed").string());
  ASSERT_EQ(compare.status, 0) << compare.err;
  const Output output = thetad(dir_, "plot --in " + (dir_ / "untimed").string() + " --out " + (dir_ / "figures").string());
  ASSERT_EQ(output.status, 0) << output.err;
  for (const auto& figure : kFigures) EXPECT_TRUE(fs::exists(dir_ / "figures" / (figure + ".png"))) << figure;
  EXPECT_THAT(read_text(dir_ / "figures" / "position.svg"), HasSubstr("hover"));
}

// Results of earlier format_versions draw as they did: version 3 as an earlier thetad wrote it
// (tests/fixtures/results; the log's wall-clock column then compute_ns) and version 1 made from it
// (no format_version, no log.columns: the helicopter's columns with compute_ns).
TEST_F(Plot, ResultsOfEarlierFormatVersionsDrawEveryFigure) {
  const fs::path fixture =
      fs::path(THETAD_SOURCE_DIR) / "tests" / "fixtures" / "results" / "hover-to-hover-theta-d-format-3";
  fs::create_directories(dir_ / "v3");
  fs::create_directories(dir_ / "v1");
  for (const char* file : {"theta-d.json", "theta-d.csv"}) {
    fs::copy_file(fixture / file, dir_ / "v3" / file);
    fs::copy_file(fixture / file, dir_ / "v1" / file);
  }
  auto result = nlohmann::ordered_json::parse(read_text(fixture / "theta-d.json"));
  result.erase("format_version");
  result["log"].erase("columns");
  result["provenance"]["scenario"].erase("text");
  write_text(dir_ / "v1" / "theta-d.json", result.dump(2));
  for (const char* version : {"v3", "v1"}) {
    const fs::path figures = dir_ / (std::string(version) + "-figures");
    const Output output = thetad(dir_, "plot --in " + (dir_ / version).string() + " --out " + figures.string());
    ASSERT_EQ(output.status, 0) << version << ": " << output.err;
    for (const auto& figure : kFigures) EXPECT_TRUE(fs::exists(figures / (figure + ".png"))) << version << " " << figure;
  }
}

// --format (or --formats) pdf: vector files a paper can print.
TEST_F(Plot, DrawsPdfOnRequest) {
  const Output output = plot("--format pdf --baseline example-pid");
  ASSERT_EQ(output.status, 0) << output.err;
  for (const auto& figure : kFigures) EXPECT_EQ(read_text(dir_ / "figures" / (figure + ".pdf")).substr(0, 5), "%PDF-") << figure;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "figures"), fs::directory_iterator()), kFigures.size());
}

TEST_F(Plot, UnknownBaselineIsAClearError) {
  const Output output = plot("--baseline nobody");
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("baseline nobody: no run of " + (dir_ / "runs").string() +
                                    " has that label (runs: lqr example-pid)"));
  expect_nothing_written();
}

TEST_F(Plot, MissingInputDirectoryIsAClearError) {
  const Output output = thetad(dir_, "plot --in " + (dir_ / "nowhere").string() + " --out " + (dir_ / "figures").string());
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("thetad: error: --in " + (dir_ / "nowhere").string() + ": no such directory"));
  expect_nothing_written();
}

TEST_F(Plot, DirectoryWithoutRunsIsAClearError) {
  fs::create_directories(dir_ / "empty");
  const Output output = thetad(dir_, "plot --in " + (dir_ / "empty").string() + " --out " + (dir_ / "figures").string());
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("no runs"));
  expect_nothing_written();
}

// A log edited after its run no longer has the SHA-256 its result records.
TEST_F(Plot, AnEditedLogIsRejected) {
  replace_once(dir_ / "runs" / "example-pid.csv", ",in_flight_step_time_ns\n", "\n");
  expect_rejected("example-pid.csv has another SHA-256 than the result records: the two files come from different runs");
}

// A result file changed after the compare is not the one its comparison.json recorded.
TEST_F(Plot, AReplacedResultIsRejected) {
  replace_once(dir_ / "runs" / "lqr.json", "\"label\": \"lqr\"", "\"label\": \"lqr\" ");
  expect_rejected("lqr.json has been replaced since the compare");
}

// Two results of different flights in one folder, without a comparison.json to join them.
TEST_F(Plot, RunsOfDifferentFlightsAreNotDrawnTogether) {
  fs::remove(dir_ / "runs" / "comparison.json");
  const Output other = thetad(dir_, "run --scenario " + (root_ / "climb.yaml").string() +
                                        " --controller other=lqr --seed 2 --out " + (dir_ / "runs").string());
  ASSERT_EQ(other.status, 0) << other.err;
  expect_rejected("flew different scenarios or seeds");
}

// A log whose result vouches for it (another thetad version's pair) but whose columns differ;
// read without the comparison (which would refuse the edited result first).
TEST_F(Plot, ColumnWithAnotherUnitIsRejected) {
  fs::remove(dir_ / "runs" / "comparison.json");
  const std::string old_digest = thetad::sha256_of_file(dir_ / "runs" / "lqr.csv");
  replace_once(dir_ / "runs" / "lqr.csv", "phi_rad,", "phi_deg,");
  replace_once(dir_ / "runs" / "lqr.json", old_digest, thetad::sha256_of_file(dir_ / "runs" / "lqr.csv"));
  expect_rejected("lqr.csv: header does not match thetad's run-log schema: column 11 is 'phi_deg', expected 'phi_rad'");
}

TEST_F(Plot, MissingColumnIsRejected) {
  fs::remove(dir_ / "runs" / "comparison.json");
  const std::string old_digest = thetad::sha256_of_file(dir_ / "runs" / "example-pid.csv");
  replace_once(dir_ / "runs" / "example-pid.csv", ",in_flight_step_time_ns\n", "\n");
  replace_once(dir_ / "runs" / "example-pid.json", old_digest, thetad::sha256_of_file(dir_ / "runs" / "example-pid.csv"));
  expect_rejected("'in_flight_step_time_ns' is missing");
}

TEST_F(Plot, MalformedSummaryJsonIsRejected) {
  fs::remove(dir_ / "runs" / "comparison.json");
  write_text(dir_ / "runs" / "lqr.json", "{\"controller\": \"lqr\",");
  expect_rejected("lqr.json: not valid JSON");
}

TEST_F(Plot, ComparisonWithoutRunsListIsRejected) {
  write_text(dir_ / "runs" / "comparison.json", "{\"scenario\": {\"name\": \"climb\"}}");
  expect_rejected("comparison.json: not a thetad comparison");
}

TEST_F(Plot, FailingScriptLeavesAnExistingOutputDirectoryAsItWas) {
  fs::create_directories(dir_ / "figures");
  write_text(dir_ / "figures" / "position.png", "old");
  const Output output = plot("", "THETAD_PYTHON=/bin/false");
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("plot_run.py failed (exit status 1)"));
  EXPECT_EQ(read_text(dir_ / "figures" / "position.png"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "figures"), fs::directory_iterator()), 1);
}

}  // namespace
