// Durability (issue 34, item 5): a run's files reach the disk before the run reports success, and
// a campaign's commits are flushed as they are made, so a power loss leaves the old result or the
// new one, never a torn one. A power loss cannot be staged in a test; the system calls can be
// watched: the program runs under strace, and the order of its fsyncs and renames is checked.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;

class Durability : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::system("strace -f -o /dev/null true >/dev/null 2>&1") != 0)
      GTEST_SKIP() << "strace is missing or may not trace here (ptrace not permitted)";
  }

  // The lines of strace's record of thetad `arguments`: fsync, fdatasync and rename calls, file
  // descriptors shown with their paths (-y), one line per call (-f with the pids kept apart).
  std::vector<std::string> traced(const std::string& arguments) const {
    const fs::path trace = dir_ / "trace.txt";
    const auto output = thetad::testing::run_thetad(
        dir_, arguments, "", {}, "strace -f -qq -y -e trace=fsync,fdatasync,rename -o " + trace.string() + " ");
    EXPECT_EQ(output.status, 0) << output.err;
    std::vector<std::string> lines;
    std::ifstream in(trace);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  // `text` as a regular expression that matches it literally (paths hold dots).
  static std::string literal(const std::string& text) {
    return std::regex_replace(text, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)");
  }

  // The index of the first line from `from` on that matches `pattern`, or -1.
  static int find(const std::vector<std::string>& lines, const std::string& pattern, int from = 0) {
    const std::regex regex(pattern);
    for (int i = from; i < static_cast<int>(lines.size()); ++i)
      if (std::regex_search(lines[static_cast<std::size_t>(i)], regex)) return i;
    return -1;
  }

  thetad::testing::ScratchDirectory scratch_{"thetad_durability_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(Durability, ARunsFilesAndTheirFolderEntriesAreOnDiskBeforeItEnds) {
  std::ofstream(dir_ / "hover.yaml") << "name: tiny\nduration: 0.2\nphases:\n  - name: hover\n    type: hold\n    time: [0, 0.2]\n";
  const std::string folder = (dir_ / "out").string(), out = literal(folder), parent = literal(dir_.string());
  const auto lines = traced("run --scenario " + (dir_ / "hover.yaml").string() + " --controller lqr --out " + folder);
  for (const std::string file : {"lqr.csv", "lqr.json"}) {
    SCOPED_TRACE(file);
    const std::string partial = out + "/\\." + literal(file) + "\\.[0-9]+\\.[0-9]+\\.partial";
    // The content, then the rename, then the folder that holds the new name and the folder's parent
    // (the folder was made by this run).
    const int content = find(lines, "f(data)?sync\\([0-9]+<" + partial + ">");
    ASSERT_GE(content, 0) << "the file was never flushed";
    const int rename = find(lines, "rename\\(\"" + partial + "\", \"" + out + "/" + literal(file) + "\"\\)", content);
    ASSERT_GE(rename, 0) << "no rename after the flush";
    EXPECT_GE(find(lines, "fsync\\([0-9]+<" + out + ">", rename), 0) << "the folder entry was not flushed";
    EXPECT_GE(find(lines, "fsync\\([0-9]+<" + parent + ">", rename), 0) << "the folder's own entry was not";
  }
}

TEST_F(Durability, ACampaignFlushesItsLogAtEveryCommit) {
  std::ofstream(dir_ / "campaign.yaml") << "campaign: tiny\nscenarios: [scenario-1]\ncontrollers: [{controller: lqr}]\n"
                                           "draws: {count: 2, base_seed: 1}\nfixed: {duration: 0.2}\n";
  const std::string folder = (dir_ / "out").string(), out = literal(folder), parent = literal(dir_.string());
  const auto lines = traced("campaign run " + (dir_ / "campaign.yaml").string() + " --out " + folder + " --quiet");
  // synchronous=FULL: the schema's commit and each batch's flush the WAL, then the checkpoint on
  // closing does; NORMAL flushes it at the checkpoint alone.
  int wal_flushes = 0;
  for (int at = find(lines, "f(data)?sync\\([0-9]+<" + out + "/campaign\\.sqlite-wal>"); at >= 0;
       at = find(lines, "f(data)?sync\\([0-9]+<" + out + "/campaign\\.sqlite-wal>", at + 1))
    ++wal_flushes;
  EXPECT_GE(wal_flushes, 3);
  // The database's entry in the folder made for it, and that folder's in its parent.
  EXPECT_GE(find(lines, "f(data)?sync\\([0-9]+<" + out + ">"), 0);
  EXPECT_GE(find(lines, "fsync\\([0-9]+<" + parent + ">"), 0);
}

}  // namespace
