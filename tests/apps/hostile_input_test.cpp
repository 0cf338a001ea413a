// What a new user gets for the inputs that used to crash, hang or lie (issue "Hostile input"):
// one line on stderr naming the file, the line and the field, a non-zero exit code, and no output
// folder or file left behind. Each test is one class of bad input, run through the real program.

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/text_file.hpp"
#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::Not;
using thetad::testing::Output;

using thetad::testing::write_text;

constexpr const char* kHover = "name: tiny\nduration: 0.2\nphases:\n  - name: hover\n    type: hold\n    time: [0, 0.2]\n";

class HostileInput : public ::testing::Test {
 protected:
  void SetUp() override { write_text(dir_ / "hover.yaml", kHover); }

  Output thetad(const std::string& arguments) const { return thetad::testing::run_thetad(dir_, arguments); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string run(const std::string& scenario, const std::string& controller) const {
    return "run --scenario " + path(scenario) + " --controller " + controller + " --out " + path("out");
  }

  // Refused: non-zero exit, one line of valid UTF-8, and nothing written.
  void expect_refused(const Output& output) const {
    EXPECT_EQ(output.status, 1) << output.err;
    EXPECT_THAT(output.err, MatchesRegex("thetad: error: [^\n]*\n")) << output.err;
    EXPECT_EQ(thetad::invalid_utf8(output.err), std::string::npos) << "not UTF-8: " << output.err;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << "an output folder was left behind";
  }

  thetad::testing::ScratchDirectory scratch_{"thetad_hostile_input_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(HostileInput, AnImpossibleDurationIsRefusedBeforeFlyingNamingTheField) {
  write_text(dir_ / "long.yaml", std::string(kHover) + "simulation:\n  duration: 1e308\n");
  Output output = thetad(run("long.yaml", "lqr"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("long.yaml") + ":8:13: field 'simulation.duration'"));
  EXPECT_THAT(output.err, HasSubstr("86400"));

  // Within the cap but with a log too large for memory: advice, before anything is allocated.
  output = thetad(run("hover.yaml", "lqr") + " --duration 80000");
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr("--log-every"));
  EXPECT_THAT(output.err, HasSubstr("--summary-only"));
}

TEST_F(HostileInput, ADesignFailureNamesTheControllerTheSettingsFileAndTheReason) {
  // Q = 0 leaves the integral states (eigenvalues 0) unobserved: no stabilising CARE solution.
  write_text(dir_ / "zero-q.yaml", "theta-d:\n  Q: [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]\n");
  const Output output = thetad(run("hover.yaml", "blind=theta-d:" + path("zero-q.yaml")));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr("controller 'blind' (theta-d, settings " + path("zero-q.yaml") + ":2:3)"));
  EXPECT_THAT(output.err, HasSubstr("CARE"));
}

TEST_F(HostileInput, ADtThatDoesNotDivideTheControllerPeriodNamesTheField) {
  write_text(dir_ / "dt.yaml", std::string(kHover) + "simulation:\n  dt: 0.0003\n");
  const Output output = thetad(run("dt.yaml", "lqr"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("dt.yaml") + ":8:7: field 'simulation.dt'"));
}

TEST_F(HostileInput, AnOutOfRangeSimulationSettingInAScenarioNamesTheFileAndTheField) {
  // Each would reach the flight loop, which says "simulate: duration must be ..." knowing neither
  // the file nor the field.
  const struct {
    const char* file;
    std::string text;
    std::string where;
  } cases[] = {
      {"short.yaml", std::string(kHover) + "simulation:\n  duration: 0.0001\n",
       ":8:13: field 'simulation.duration': the flight (0.0001 s) is shorter than one controller period (0.001 s"},
      {"day.yaml", "name: day\nduration: 1e5\nphases:\n  - name: hover\n    type: hold\n    time: [0, 1e5]\n",
       ":2:11: field 'duration': at most 86400 s (one simulated day)"},
      {"steps.yaml", std::string(kHover) + "simulation:\n  controller_period_steps: 1000000\n",
       ":8:28: field 'simulation.controller_period_steps': the flight (0.2 s) is shorter than one controller period"},
      {"samples.yaml", std::string(kHover) + "simulation:\n  duration: 20\n  dt: 1e-9\n  controller_period_steps: 1\n",
       ":9:7: field 'simulation.dt': a controller period of 1e-09 s gives more than 1e10 controller samples"},
      {"tiny.yaml", std::string(kHover) + "simulation:\n  dt: 1e-13\n",
       ":8:7: field 'simulation.dt': 1e-13 s: more than 2^31 - 1 plant steps per controller period"},
  };
  for (const auto& bad : cases) {
    write_text(dir_ / bad.file, bad.text);
    const Output output = thetad(run(bad.file, "lqr"));
    expect_refused(output);
    EXPECT_THAT(output.err, HasSubstr(path(bad.file) + bad.where));
  }
}

TEST_F(HostileInput, ASettingsBlockOfTheWrongTypeIsReportedUnderTheBlocksName) {
  write_text(dir_ / "number.yaml", "theta-d: 5\n");
  Output output = thetad(run("hover.yaml", "theta-d:" + path("number.yaml")));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("number.yaml") + ":1:10: field 'theta-d': expected a map of fields, got '5'"));

  // A block this run does not fly, through --settings.
  write_text(dir_ / "list.yaml", "lqr: {}\nsdre: [1, 2]\n");
  output = thetad(run("hover.yaml", "lqr") + " --settings " + path("list.yaml"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("list.yaml") + ":2:7: field 'sdre': expected a map of fields, got a sequence"));
}

TEST_F(HostileInput, AnEmptyLabelIsRefused) {
  Output output = thetad(run("hover.yaml", "=theta-d"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr("controller '=theta-d': an empty label before '='"));

  write_text(dir_ / "controllers.yaml", "controllers:\n  - label: ''\n    controller: lqr\n");
  output = thetad("compare --scenario " + path("hover.yaml") + " --controllers-file " + path("controllers.yaml") +
                  " --out " + path("out"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("controllers.yaml") + ":2:12: field 'controllers[0].label': an empty label"));
}

TEST_F(HostileInput, UserTextWithInvalidUtf8IsEscapedInTheErrorLine) {
  // Raw bytes in single quotes: /bin/sh (dash) passes them through as they are.
  Output output = thetad(run("hover.yaml", "'caf\xc3=lqr'"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr("controller 'caf\\xC3=lqr': label 'caf\\xC3': a label names files"));

  output = thetad(run("hover.yaml", "'th\xff-d'"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr("unknown controller 'th\\xFF-d'"));

  output = thetad(run("hover.yaml", "'theta-d:" + path("s\xfe.yaml") + "'"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr("cannot read " + path("s\\xFE.yaml")));

  output = thetad("run --scenario 'hover\xe9' --controller lqr --out " + path("out"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr("scenario 'hover\\xE9': no such file"));

  // The command-line parser's own messages quote arguments too.
  output = thetad(run("hover.yaml", "lqr") + " '--d\xe9" "bug'");
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr("--d\\xE9bug"));
}

TEST_F(HostileInput, SeedsAreUnsigned64BitNumbersOrAnError) {
  for (const char* seed : {"-1", "18446744073709551616", "''", "1.5", "0x10"}) {
    const Output output = thetad(run("hover.yaml", "lqr") + " --seed " + seed);
    expect_refused(output);
    EXPECT_THAT(output.err, HasSubstr("--seed")) << seed;
  }
  write_text(dir_ / "seed.yaml", std::string(kHover) + "simulation:\n  seed: -1\n");
  const Output output = thetad(run("seed.yaml", "lqr"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("seed.yaml") + ":8:9: field 'simulation.seed'"));
}

TEST_F(HostileInput, ADuplicateKeyNamesBothLines) {
  write_text(dir_ / "dup.yaml", "theta-d:\n  terms: 3\n  fixed_point_iterations: 2\n  terms: 2\n");
  Output output = thetad(run("hover.yaml", "theta-d:" + path("dup.yaml")));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("dup.yaml") + ":4:3: key 'terms' given twice in one map (first at line 2)"));

  write_text(dir_ / "dup-scenario.yaml", std::string(kHover) + "duration: 0.1\n");
  output = thetad(run("dup-scenario.yaml", "lqr"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("dup-scenario.yaml") + ":7:1: key 'duration' given twice in one map (first at line 2)"));
}

TEST_F(HostileInput, DirectoriesDevicesAndFifosAreNotInputFiles) {
  fs::create_directory(dir_ / "folder.yaml");
  Output output = thetad(run("hover.yaml", "lqr") + " --settings " + path("folder.yaml"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("folder.yaml") + ": a directory, not a regular file"));

  // Read forever before: now refused at once.
  output = thetad("run --scenario /dev/zero --controller lqr --out " + path("out"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr("/dev/zero"));

  ASSERT_EQ(mkfifo((dir_ / "pipe.yaml").c_str(), 0600), 0);
  output = thetad(run("hover.yaml", "theta-d:" + path("pipe.yaml")));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("pipe.yaml") + ": a FIFO (named pipe), not a regular file"));
}

TEST_F(HostileInput, AnInputFileOverTheSizeCapIsRefusedUnread) {
  {
    std::ofstream big(dir_ / "big.yaml", std::ios::binary);
    big << "# padding\n";
    big.seekp((std::streamoff{64} << 20) + 1);
    big << '\n';
  }
  const Output output = thetad(run("big.yaml", "lqr"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("big.yaml") + ": 67108866 bytes, more than the 64 MiB"));
}

TEST_F(HostileInput, ATypoInABlockThatThisRunDoesNotFlyIsFoundNow) {
  write_text(dir_ / "settings.yaml", "theta-d:\n  terms: 3\nsdre:\n  mdoe: warm\n");
  Output output = thetad(run("hover.yaml", "theta-d:" + path("settings.yaml")));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("settings.yaml") + ":4:3: field 'mdoe'"));

  // The same through --settings, and a bad value rather than a bad key.
  write_text(dir_ / "settings.yaml", "lqr: {}\nsdre:\n  mode: warn\n");
  output = thetad(run("hover.yaml", "lqr") + " --settings " + path("settings.yaml"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("settings.yaml") + ":3:9: field 'mode'"));
}

TEST_F(HostileInput, NamesMustBeValidUtf8) {
  write_text(dir_ / "name.yaml", "name: \"bad\xff\"\n" + std::string(kHover).substr(std::string(kHover).find('\n') + 1));
  Output output = thetad(run("name.yaml", "lqr"));
  expect_refused(output);
  EXPECT_THAT(output.err, HasSubstr(path("name.yaml") + ":1:11: not valid UTF-8"));
}

TEST_F(HostileInput, AControllerThatThrowsOrReturnsNanFailsItsRunAndTheOthersGoOn) {
  write_text(dir_ / "faults.yaml", "faulty:\n  fault: throw\n  at: 0.05\n");
  write_text(dir_ / "nan.yaml", "faulty:\n  fault: nan\n  at: 0.1\n");
  const Output output = thetad("compare --plugin " + std::string(THETAD_FAULTY_PLUGIN) + " --scenario " + path("hover.yaml") +
                               " --controllers thrower=faulty:" + path("faults.yaml") + ",lqr,nan=faulty:" + path("nan.yaml") +
                               " --out " + path("out"));
  EXPECT_EQ(output.status, 3) << output.err;
  EXPECT_THAT(output.err, Not(HasSubstr("error")));
  const auto result = [&](const std::string& label) {
    return nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / (label + ".json")));
  };
  const auto thrower = result("thrower"), good = result("lqr"), nan = result("nan");
  EXPECT_EQ(thrower["status"], "failed");
  EXPECT_EQ(thrower["reason"], "controller failed at t = 0.0500 s: the user's code threw");
  EXPECT_EQ(nan["status"], "failed");
  EXPECT_EQ(nan["reason"], "controller failed at t = 0.1000 s: non-finite command");
  EXPECT_EQ(good["status"], "completed");
  EXPECT_THAT(output.out, HasSubstr("thrower"));
  EXPECT_THAT(output.out, HasSubstr("failed at 0.050 s"));
  // The log of a failed run ends before the failure: no NaN row.
  EXPECT_EQ(thetad::testing::read_text(dir_ / "out" / "nan.csv").find("nan"), std::string::npos);
}

TEST_F(HostileInput, AFileSizeLimitWhileWritingIsAClearErrorAndLeavesNoPartialFile) {
  // ulimit -f counts 1024-byte blocks: 16 KiB holds the JSON but not the log of 200 samples.
  const std::string command = "bash -c 'ulimit -f 16; exec \"$0\" \"$@\"' ";
  const Output output = thetad::testing::run_thetad(
      dir_, run("hover.yaml", "lqr"), "", {}, command);
  EXPECT_EQ(output.status, 1) << output.err;
  EXPECT_THAT(output.err, HasSubstr("cannot write " + path("out/lqr.csv") + ": File too large"));
  ASSERT_TRUE(fs::is_directory(dir_ / "out"));  // created and probed before flying
  EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "a partial or unpaired file was left behind";
}

// The command prefix that runs a command in a private mount namespace, where it may mount a small
// or a read-only file system that no other process sees: as root (`unshare --mount`), else in a
// user namespace that maps the caller to root. Empty when neither is allowed here.
std::string private_mount_namespace() {
  for (const char* unshare : {"unshare --mount", "unshare --user --map-root-user --mount"}) {
    if (std::system((std::string(unshare) + " true >/dev/null 2>&1").c_str()) == 0) return unshare;
  }
  return {};
}

// Runs thetad with `arguments` after `mount` (shell commands) in a private mount namespace, and
// writes what is left in `folder` when thetad has ended (the mounts end with the namespace) to
// left.txt.
Output run_in_private_mounts(const fs::path& dir, const std::string& unshare, const std::string& mount,
                             const std::string& folder, const std::string& arguments) {
  const std::string launcher = unshare + " sh -c '" + mount + " && \"$0\" \"$@\"; status=$?; ls -A " + folder +
                               " >" + (dir / "left.txt").string() + "; exit $status' ";
  return thetad::testing::run_thetad(dir, arguments, "", {}, launcher);
}

TEST_F(HostileInput, AFullDiskWhileWritingIsAClearErrorAndLeavesNoPartialFile) {
  const std::string unshare = private_mount_namespace();
  if (unshare.empty()) GTEST_SKIP() << "no private mount namespace here (unshare --mount is not permitted) to mount a small file system";
  // A 16 KiB file system: the output folder and its probe fit, the log of 200 samples does not.
  fs::create_directory(dir_ / "disk");
  const std::string disk = path("disk");
  const Output output =
      run_in_private_mounts(dir_, unshare, "mount -t tmpfs -o size=16k tmpfs " + disk, disk + "/out",
                            "run --scenario " + path("hover.yaml") + " --controller lqr --out " + disk + "/out");
  EXPECT_EQ(output.status, 1) << output.err;
  EXPECT_THAT(output.err, HasSubstr("thetad: error: cannot write " + disk + "/out/lqr.csv: No space left on device"));
  EXPECT_EQ(thetad::testing::read_text(dir_ / "left.txt"), "") << "a partial or unpaired file was left behind";
}

TEST_F(HostileInput, AReadOnlyOutputFolderIsAnErrorBeforeFlying) {
  const std::string unshare = private_mount_namespace();
  if (unshare.empty()) GTEST_SKIP() << "no private mount namespace here (unshare --mount is not permitted) to mount a read-only file system";
  // Read-only for root too: a file system mounted read-only, with the output folder already on it.
  fs::create_directory(dir_ / "disk");
  const std::string disk = path("disk");
  const std::string mount = "mount -t tmpfs -o size=1m tmpfs " + disk + " && mkdir " + disk + "/out && mount -o remount,ro " + disk;
  Output output = run_in_private_mounts(dir_, unshare, mount, disk + "/out",
                                        "run --scenario " + path("hover.yaml") + " --controller lqr --out " + disk + "/out");
  EXPECT_EQ(output.status, 1) << output.err;
  EXPECT_THAT(output.err, MatchesRegex("thetad: error: [^\n]*\n")) << output.err;
  EXPECT_THAT(output.err, HasSubstr("--out " + disk + "/out: cannot write there: Read-only file system"));
  EXPECT_EQ(output.out, "") << "flew before finding that it could not write";
  EXPECT_EQ(thetad::testing::read_text(dir_ / "left.txt"), "");

  // An output folder still to be made on a read-only file system.
  output = run_in_private_mounts(dir_, unshare, mount, disk,
                                 "run --scenario " + path("hover.yaml") + " --controller lqr --out " + disk + "/new");
  EXPECT_EQ(output.status, 1) << output.err;
  EXPECT_THAT(output.err, HasSubstr("--out " + disk + "/new: cannot create the folder: Read-only file system"));
  EXPECT_EQ(output.out, "");
  EXPECT_EQ(thetad::testing::read_text(dir_ / "left.txt"), "out\n");
}

}  // namespace
