// What `thetad run` and `thetad compare` leave behind, as a user (or a cluster's scheduler) treats
// them: exit codes, labels, summary-only results, progress lines, and outputs that stay consistent
// when runs share a folder, are killed half-way or get a signal while writing.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "experiment/run_files.hpp"
#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using thetad::testing::Output;

class RunOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    write("hover.yaml", "name: tiny\nduration: 2\nphases:\n  - name: hover\n    type: hold\n    time: [0, 2]\n");
    // Rolled past the divergence limit (85 degrees) from the start.
    write("upset.yaml", "name: upset\nduration: 2\ninitial_state:\n  attitude: [1.6, 0, 0]\n"
                        "phases:\n  - name: hover\n    type: hold\n    time: [0, 2]\n");
    write("tuned.yaml", "theta-d:\n  k: [0.5, 0.25]\n  l: [2, 3]\n");
  }
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  Output thetad(const std::string& arguments, const std::string& environment = "") const {
    return thetad::testing::run_thetad(dir_, arguments, environment);
  }
  // thetad run from the folder `cwd` (relative paths in `arguments` are relative to it).
  Output thetad_in(const fs::path& cwd, const std::string& arguments) const {
    return thetad::testing::run_thetad(dir_, arguments, "", cwd);
  }
  // thetad started in the background; its pid.
  pid_t start(const std::vector<std::string>& arguments) const {
    const pid_t child = fork();
    if (child == 0) {
      setenv("CI", "1", 1);
      std::freopen((dir_ / ("bg-" + std::to_string(getpid()) + ".err")).c_str(), "w", stderr);
      std::freopen("/dev/null", "w", stdout);
      std::vector<char*> argv{const_cast<char*>(THETAD_BINARY)};
      for (const auto& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
      argv.push_back(nullptr);
      execv(THETAD_BINARY, argv.data());
      _exit(127);
    }
    return child;
  }
  static int wait_for(pid_t child) {
    int status = 0;
    waitpid(child, &status, 0);
    return status;
  }
  // Waits (up to a minute) until `predicate` holds.
  template <class Predicate>
  static bool eventually(Predicate predicate) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (std::chrono::steady_clock::now() < end) {
      if (predicate()) return true;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    return false;
  }
  // The temporary files in `folder` whose names start with `prefix`.
  static std::vector<std::string> partial_files(const fs::path& folder, const std::string& prefix = ".") {
    std::vector<std::string> found;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(folder, error)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind(prefix, 0) == 0 && name.find(".partial") != std::string::npos) found.push_back(name);
    }
    return found;
  }

  thetad::testing::ScratchDirectory scratch_{"thetad_run_outputs_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(RunOutputs, VersionNamesTheProgram) {
  const Output output = thetad("--version");
  EXPECT_EQ(output.status, 0);
  EXPECT_THAT(output.out, ::testing::StartsWith("thetad 0.1.0 ("));
}

TEST_F(RunOutputs, ExitCodeIsZeroWhenCompletedAndThreeWhenARunDiverged) {
  Output output = thetad("run --scenario " + path("hover.yaml") + " --controller lqr --ideal --out " + path("out"));
  EXPECT_EQ(output.status, 0) << output.err;
  output = thetad("run --scenario " + path("upset.yaml") + " --controller lqr --ideal --out " + path("out"));
  EXPECT_EQ(output.status, 3) << output.err;
  EXPECT_THAT(output.out, HasSubstr("diverged at 0.000 s"));
  output = thetad("compare --scenario " + path("upset.yaml") + " --controllers lqr,theta-d --ideal --out " +
                  path("both"));
  EXPECT_EQ(output.status, 3) << output.err;
  EXPECT_TRUE(fs::exists(dir_ / "both" / "comparison.json"));
}

TEST_F(RunOutputs, ALabelledCompareFliesOneControllerTwiceUnderItsLabels) {
  const Output output = thetad("compare --scenario " + path("hover.yaml") + " --controllers paper=theta-d,tuned=theta-d:" +
                               path("tuned.yaml") + ",lqr --duration 0.5 --out " + path("out"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("\npaper "));
  EXPECT_THAT(output.out, HasSubstr("\ntuned "));
  const auto comparison = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "comparison.json"));
  ASSERT_EQ(comparison["runs"].size(), 3u);
  EXPECT_EQ(comparison["runs"][1]["label"], "tuned");
  EXPECT_EQ(comparison["runs"][1]["controller"], "theta-d");
  const thetad::StoredRun tuned = thetad::read_run_files(dir_ / "out" / "tuned.json");
  EXPECT_EQ(tuned.result["controller_settings"]["k"], nlohmann::ordered_json::array({0.5, 0.25}));
  EXPECT_EQ(tuned.result["settings_source"], path("tuned.yaml"));
  EXPECT_NE(tuned.result["cost"], thetad::read_run_files(dir_ / "out" / "paper.json").result["cost"]);

  const Output twice = thetad("compare --scenario " + path("hover.yaml") + " --controllers theta-d,theta-d --out " +
                              path("twice"));
  EXPECT_NE(twice.status, 0);
  EXPECT_THAT(twice.err, HasSubstr("label 'theta-d' is used twice"));
  EXPECT_FALSE(fs::exists(dir_ / "twice"));
}

TEST_F(RunOutputs, AControllersFileListsLabelledSpecs) {
  write("controllers.yaml", "controllers:\n  - {label: paper, controller: theta-d}\n"
                            "  - {label: tuned, controller: theta-d, settings: tuned.yaml}\n"
                            "  - {label: cold, controller: sdre, settings: {mode: cold}}\n");
  Output output = thetad("compare --scenario " + path("hover.yaml") + " --controllers-file " + path("controllers.yaml") +
                         " --duration 0.3 --summary-only --out " + path("out"));
  ASSERT_EQ(output.status, 0) << output.err;
  const auto comparison = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "comparison.json"));
  ASSERT_EQ(comparison["runs"].size(), 3u);
  EXPECT_EQ(comparison["runs"][2]["label"], "cold");
  EXPECT_EQ(thetad::read_run_files(dir_ / "out" / "cold.json").result["controller_settings"]["mode"], "cold");
  EXPECT_EQ(thetad::read_run_files(dir_ / "out" / "tuned.json").result["controller_settings"]["k"][1], 0.25);

  output = thetad("compare --scenario " + path("hover.yaml") + " --controllers lqr --controllers-file " +
                  path("controllers.yaml") + " --out " + path("both"));
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("--controllers or --controllers-file (one of them)"));
  write("typo.yaml", "controlers: []\n");
  output = thetad("compare --scenario " + path("hover.yaml") + " --controllers-file " + path("typo.yaml") + " --out " +
                  path("typo"));
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr(path("typo.yaml") + ":1:1: field 'controlers': unknown field"));
}

TEST_F(RunOutputs, NoTimingRerunsOfOneSeedWriteByteIdenticalFiles) {
  for (const char* folder : {"a", "b"}) {
    const Output output = thetad("run --scenario " + path("hover.yaml") + " --controller theta-d --no-timing --out " +
                                 path(folder));
    ASSERT_EQ(output.status, 0) << output.err;
  }
  for (const char* file : {"theta-d.csv", "theta-d.json"}) {
    EXPECT_EQ(thetad::testing::read_text(dir_ / "a" / file), thetad::testing::read_text(dir_ / "b" / file)) << file;
  }
  const std::string result = thetad::testing::read_text(dir_ / "a" / "theta-d.json");
  for (const char* wall_clock : {"host", "start_time", "wall_time_s", "in_flight_step_time"})
    EXPECT_THAT(result, Not(HasSubstr(wall_clock))) << wall_clock;
}

TEST_F(RunOutputs, SummaryOnlyWritesACompleteResultAndNoLog) {
  const Output output = thetad("run --scenario " + path("hover.yaml") + " --controller theta-d --summary-only --out " +
                               path("out"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "theta-d.csv"));
  const thetad::StoredRun run = thetad::read_run_files(dir_ / "out" / "theta-d.json");
  EXPECT_TRUE(run.result["log"].is_null());
  EXPECT_EQ(run.result["controller_samples"], 2000);
  EXPECT_TRUE(run.result["cost"].get<double>() > 0.0);
  EXPECT_EQ(run.result["provenance"]["scenario"]["file"], path("hover.yaml"));
  EXPECT_EQ(run.result["provenance"]["scenario"]["sha256"].get<std::string>().size(), 64u);
}

TEST_F(RunOutputs, AReplayFliesTheRecordedRunAgainAndSaysWhetherItAgrees) {
  ASSERT_EQ(thetad("run --scenario " + path("hover.yaml") + " --controller paper=theta-d --seed 4 --log-every 3 --out " +
                   path("out")).status, 0);
  // From another folder (the result records the scenario's absolute path), into a third one.
  fs::create_directories(dir_ / "elsewhere");
  Output output = thetad_in(dir_ / "elsewhere", "run --replay ../out/paper.json --out replayed");
  EXPECT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("agrees with the recorded run"));
  EXPECT_TRUE(fs::exists(dir_ / "elsewhere" / "replayed" / "paper.json"));
  output = thetad("run --replay " + path("out/paper.json") + " --out " + path("out"));
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("would overwrite"));

  std::string result = thetad::testing::read_text(dir_ / "out" / "paper.json");
  result.insert(result.find("\"cost\": ") + 8, "9");
  write("edited.json", result);
  output = thetad("run --replay " + path("edited.json"));
  EXPECT_EQ(output.status, 4);
  EXPECT_THAT(output.out, HasSubstr("DIFFERS"));
  EXPECT_THAT(output.out, HasSubstr("cost: recorded"));

  write("not-a-result.json", "{}");
  output = thetad("run --replay " + path("not-a-result.json"));
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("not a thetad run result"));

  // A result of an earlier format_version (3, tests/fixtures/results) replays, and the replay is
  // written with the current names.
  output = thetad("run --replay " THETAD_SOURCE_DIR
                  "/tests/fixtures/results/hover-to-hover-theta-d-format-3/theta-d.json --out " + path("again"));
  EXPECT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("agrees with the recorded run (completed)"));
  const auto again = nlohmann::json::parse(thetad::testing::read_text(dir_ / "again" / "theta-d.json"));
  EXPECT_EQ(again["format_version"], thetad::kRunFormatVersion);
  EXPECT_EQ(again["cost"].get<double>(), 659.3368505702687);
}

// --set takes any campaign factor for one flight, read and checked as in a campaign file.
TEST_F(RunOutputs, SetGivesACampaignFactorToOneFlight) {
  const Output output = thetad("run --scenario " + path("hover.yaml") + " --controller lqr --duration 0.2 --set " +
                               "turbulence_model=dryden --set turbulence_intensity=severe --set noise_scale=0 --out " +
                               path("set"));
  ASSERT_EQ(output.status, 0) << output.err;
  const nlohmann::json result = nlohmann::json::parse(thetad::testing::read_text(dir_ / "set" / "lqr.json"));
  EXPECT_EQ(result["settings"]["turbulence"]["model"], "dryden");
  EXPECT_EQ(result["settings"]["turbulence"]["intensity"], "severe");
  EXPECT_EQ(result["settings"]["noise"]["scale"], 0.0);
  const Output stormy = thetad("run --scenario " + path("hover.yaml") + " --controller lqr --set turbulence_intensity=stormy");
  EXPECT_NE(stormy.status, 0);
  EXPECT_THAT(stormy.err, HasSubstr("turbulence_intensity: expected one of light moderate severe"));
  const Output unknown = thetad("run --scenario " + path("hover.yaml") + " --controller lqr --set windiness=3");
  EXPECT_THAT(unknown.err, HasSubstr("'windiness=3': expected NAME=VALUE with NAME one of uncertainty_scale"));
  const Output slowdown =
      thetad("run --scenario " + path("hover.yaml") + " --controller lqr --set slowdown=3 --out " + path("slow"));
  EXPECT_THAT(slowdown.err, HasSubstr("slowdown: only for a flight computer"));
}

TEST_F(RunOutputs, TheOutputFolderIsCheckedBeforeAnythingFlies) {
  write("file", "not a folder");
  const Output output = thetad("run --scenario " + path("hover.yaml") + " --controller lqr --out " + path("file"));
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("--out " + path("file")));
  EXPECT_THAT(output.err, Not(HasSubstr("flying")));
  const Output proc = thetad("compare --scenario " + path("hover.yaml") + " --controllers lqr --out /proc/thetad-out");
  EXPECT_EQ(proc.status, 1);
  EXPECT_THAT(proc.err, Not(HasSubstr("flying")));
}

TEST_F(RunOutputs, WithoutATerminalProgressComesAsPlainLinesWithRateAndEta) {
  Output output = thetad("run --scenario " + path("hover.yaml") + " --controller theta-d --out " + path("out"),
                         "THETAD_PROGRESS_INTERVAL=0");
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.err, HasSubstr("theta-d: flying (2 s simulated)"));
  EXPECT_THAT(output.err, HasSubstr("x real time, ETA "));
  EXPECT_THAT(output.err, Not(HasSubstr("\033")));
  output = thetad("run --scenario " + path("hover.yaml") + " --controller theta-d --quiet --out " + path("out"));
  EXPECT_EQ(output.err, "");
}

// On a terminal (script(1) gives the program one) the progress is one line redrawn in place.
TEST_F(RunOutputs, OnATerminalProgressIsOneLineRedrawnWithRateAndEta) {
  if (!fs::exists("/usr/bin/script")) GTEST_SKIP() << "no script(1) to give thetad a terminal";
  const std::string command = "env -u CI /usr/bin/script -qec '" + std::string(THETAD_BINARY) + " run --scenario " +
                              THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml --controller theta-d --duration 60 " +
                              "--summary-only --out " + path("live") + "' /dev/null > " + path("terminal.txt");
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string screen = thetad::testing::read_text(dir_ / "terminal.txt");
  EXPECT_THAT(screen, HasSubstr("\r\033[Ktheta-d: "));
  EXPECT_THAT(screen, HasSubstr("x real time, ETA "));
  EXPECT_THAT(screen, HasSubstr("theta-d: completed"));
  EXPECT_THAT(screen, Not(HasSubstr("flying (60 s simulated)")));  // the plain-lines form
}

TEST_F(RunOutputs, ConcurrentRunsOfOneLabelInOneFolderLeaveAConsistentPair) {
  for (int round = 0; round < 3; ++round) {
    std::vector<pid_t> runs;
    for (const char* seed : {"1", "2"})
      runs.push_back(start({"run", "--scenario", path("hover.yaml"), "--controller", "lqr", "--seed", seed, "--out",
                            path("shared")}));
    for (const pid_t run : runs) {
      const int status = wait_for(run);
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
    EXPECT_NO_THROW(thetad::read_run_files(dir_ / "shared" / "lqr.json"));
    EXPECT_TRUE(partial_files(dir_ / "shared").empty());
  }
}

TEST_F(RunOutputs, ACompareKilledHalfWayLeavesNoComparisonAndOnlyWholeRuns) {
  ASSERT_EQ(thetad("compare --scenario " + path("hover.yaml") + " --controllers lqr --out " + path("out")).status, 0);
  ASSERT_TRUE(fs::exists(dir_ / "out" / "comparison.json"));
  const pid_t compare = start({"compare", "--scenario", THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml", "--controllers",
                               "lqr,sdre", "--duration", "30", "--out", path("out")});
  // Killed once the first run is written, while the second flies. Until then the old lqr.json may
  // sit beside the new lqr.csv, a pair the reader refuses.
  const auto new_lqr_written = [&] {
    try {
      return !fs::exists(dir_ / "out" / "comparison.json") &&
             thetad::read_run_files(dir_ / "out" / "lqr.json").result["end_time_s"] == 30.0;
    } catch (const thetad::Error&) {
      return false;
    }
  };
  ASSERT_TRUE(eventually(new_lqr_written));
  kill(compare, SIGTERM);
  const int status = wait_for(compare);
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "comparison.json"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "sdre.json"));
  EXPECT_TRUE(partial_files(dir_ / "out").empty());
  EXPECT_NO_THROW(thetad::read_run_files(dir_ / "out" / "lqr.json"));
}

TEST_F(RunOutputs, SigtermWhileWritingLeavesNoPartialFile) {
  const pid_t run = start({"run", "--scenario", THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml", "--controller", "lqr",
                           "--duration", "60", "--out", path("out")});
  // The log being written (not the output folder's write probe before the flight).
  ASSERT_TRUE(eventually([&] { return !partial_files(dir_ / "out", ".lqr.csv.").empty(); }));
  kill(run, SIGTERM);
  const int status = wait_for(run);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  EXPECT_TRUE(partial_files(dir_ / "out").empty());
  EXPECT_FALSE(fs::exists(dir_ / "out" / "lqr.json"));
}

}  // namespace
