#include "experiment/run_files.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "experiment/flight.hpp"
#include "experiment/sha256.hpp"
#include "tests/error_message.hpp"
#include "tests/scratch_directory.hpp"

namespace thetad {
namespace {

using testing::error_message;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

RunResult short_run(const std::string& label, bool summary_only = false, std::uint64_t seed = 1) {
  RunControls controls;
  controls.duration = 0.05;
  controls.seed = seed;
  controls.summary_only = summary_only;
  const Flight flight(THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml", controls);
  PreparedController prepared = flight.prepare(parse_controller_spec(label + "=lqr"));
  return flight.fly(prepared);
}

class RunFilesTest : public ::testing::Test {
 protected:
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  testing::ScratchDirectory scratch_{"thetad_run_files_test"};
  const fs::path dir_ = scratch_.path();
};

TEST(Sha256, KnownDigests) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST_F(RunFilesTest, TheResultNamesItsLogWithItsDigestAndReadsBack) {
  const RunFiles files = write_run_files(short_run("a"), dir_);
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.csv", "a.json"}));
  const StoredRun run = read_run_files(files.json);
  EXPECT_EQ(run.label, "a");
  EXPECT_EQ(run.csv_file, files.csv);
  EXPECT_EQ(run.result["log"]["sha256"], sha256_of_file(files.csv));
  EXPECT_EQ(run.result["log"]["rows"], 50);
  EXPECT_EQ(run.result["controller"], "lqr");
  EXPECT_EQ(run.columns.size(), sim::helicopter_log_schema().size());
}

TEST_F(RunFilesTest, ALogFromAnotherRunIsRefused) {
  write_run_files(short_run("a", false, 1), dir_ / "one");
  write_run_files(short_run("a", false, 2), dir_ / "two");
  // What a kill between the two renames of a rerun leaves: the new log beside the old result.
  fs::copy_file(dir_ / "two" / "a.csv", dir_ / "one" / "a.csv", fs::copy_options::overwrite_existing);
  EXPECT_THAT(error_message([&] { read_run_files(dir_ / "one" / "a.json"); }), HasSubstr("come from different runs"));
  fs::remove(dir_ / "one" / "a.csv");
  EXPECT_THAT(error_message([&] { read_run_files(dir_ / "one" / "a.json"); }), HasSubstr("is missing"));
}

TEST_F(RunFilesTest, ASummaryOnlyResultHasNoLogAndRemovesAStaleOne) {
  write_run_files(short_run("a"), dir_);
  const RunFiles files = write_run_files(short_run("a", true), dir_);
  EXPECT_TRUE(files.csv.empty());
  EXPECT_EQ(entries(), std::vector<std::string>{"a.json"});
  const StoredRun run = read_run_files(files.json);
  EXPECT_TRUE(run.csv_file.empty());
  EXPECT_TRUE(run.result["log"].is_null());
  EXPECT_EQ(run.result["controller_samples"], 50);
}

TEST_F(RunFilesTest, AFailedCommitLeavesNothing) {
  fs::create_directories(dir_ / "a.json" / "occupied");
  EXPECT_THROW(write_run_files(short_run("a"), dir_), Error);
  EXPECT_EQ(entries(), std::vector<std::string>{"a.json"});
  fs::remove_all(dir_ / "a.json");
  std::ofstream(dir_ / "file") << "x";
  EXPECT_THROW(write_run_files(short_run("b"), dir_ / "file" / "below"), Error);
  EXPECT_EQ(entries(), std::vector<std::string>{"file"});
}

TEST_F(RunFilesTest, AFolderListsItsResultsInNameOrderAndIgnoresOtherJson) {
  write_run_files(short_run("b"), dir_);
  write_run_files(short_run("a", true), dir_);
  std::ofstream(dir_ / "notes.json") << "{\"x\": 1}";
  const std::vector<StoredRun> runs = read_result_folder(dir_);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].label, "a");
  EXPECT_EQ(runs[1].label, "b");
  EXPECT_THAT(error_message([&] { read_result_folder(dir_ / "none"); }), HasSubstr("no such directory"));
}

// Writers racing on one label: each commit is whole (the folder is locked around the renames), so
// whatever the interleaving the folder ends with a pair of one run.
TEST_F(RunFilesTest, RacingCommitsOfOneLabelLeaveAConsistentPair) {
  const RunResult one = short_run("a", false, 1), two = short_run("a", false, 2);
  for (int round = 0; round < 40; ++round) {
    std::thread first([&] { write_run_files(one, dir_); });
    std::thread second([&] { write_run_files(two, dir_); });
    first.join();
    second.join();
    ASSERT_NO_THROW(read_run_files(dir_ / "a.json")) << "round " << round;
  }
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.csv", "a.json"}));
}

TEST_F(RunFilesTest, PartialNamesAreUniquePerWriteAndRemovedUnlessCommitted) {
  std::string first, second;
  {
    const PartialFile a(dir_ / "x.csv"), b(dir_ / "x.csv");
    first = a.path().filename().string();
    second = b.path().filename().string();
    std::ofstream(a.path()) << "a";
    std::ofstream(b.path()) << "b";
  }
  EXPECT_NE(first, second);
  EXPECT_THAT(first, HasSubstr(".x.csv." + std::to_string(getpid()) + "."));
  EXPECT_TRUE(entries().empty());
}

TEST_F(RunFilesTest, ATerminatingSignalRemovesThePartialFilesAndStillEndsTheProcess) {
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const PartialFile partial(dir_ / "run.csv");
    std::ofstream(partial.path()) << "half a log";
    std::raise(SIGTERM);
    _exit(0);  // not reached: the signal ends the process
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_TRUE(entries().empty());
}

TEST_F(RunFilesTest, AnOutputFolderIsCheckedBeforeAnythingFlies) {
  prepare_output_folder(dir_ / "new" / "folder");
  EXPECT_TRUE(fs::is_directory(dir_ / "new" / "folder"));
  std::ofstream(dir_ / "file") << "x";
  EXPECT_THAT(error_message([&] { prepare_output_folder(dir_ / "file"); }), HasSubstr("--out"));
  // Read-only even for root.
  EXPECT_THAT(error_message([&] { prepare_output_folder("/proc/thetad-out"); }), HasSubstr("--out /proc/thetad-out"));
  if (geteuid() != 0) {  // root writes anywhere
    fs::create_directories(dir_ / "read-only");
    fs::permissions(dir_ / "read-only", fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THAT(error_message([&] { prepare_output_folder(dir_ / "read-only"); }), HasSubstr("cannot write there"));
  }
}

}  // namespace
}  // namespace thetad
