// `thetad campaign` as a user (or a cluster job) runs it: killed and resumed, under mpirun, and
// with a bad campaign file.
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "tests/apps/run_thetad.hpp"
#include "tests/campaigns/campaign_testing.hpp"
#include "tests/scratch_directory.hpp"

namespace thetad {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::expect_same_runs;
using testing::run_thetad;
using testing::stored_records;

class CampaignCommand : public ::testing::Test {
 protected:
  fs::path write_campaign(const std::string& text) const {
    const fs::path file = scratch_.path() / "campaign.yaml";
    std::ofstream(file) << text;
    return file;
  }
  testing::ScratchDirectory scratch_{"campaign_command_test"};
};

TEST_F(CampaignCommand, AKilledCampaignResumedEqualsAnUninterruptedOne) {
  // The SDRE solves a Riccati equation every step: 16 runs of 0.3 s take a few seconds, long
  // enough to kill the campaign in the middle.
  const fs::path file = write_campaign(R"(campaign: kill-test
scenarios: [scenario-1]
controllers: [{controller: sdre}, {controller: lqr}]
draws: {count: 8, base_seed: 3}
fixed: {duration_s: 0.3}
)");
  const fs::path killed = scratch_.path() / "killed";
  const std::string command = "CI=1 " + std::string(THETAD_BINARY) + " campaign run " + file.string() + " --out " +
                              killed.string() + " --no-timing --jobs 1 >/dev/null 2>&1 & echo $!";
  FILE* shell = popen(command.c_str(), "r");
  ASSERT_NE(shell, nullptr);
  long pid = 0;
  ASSERT_EQ(std::fscanf(shell, "%ld", &pid), 1);
  pclose(shell);
  // Kill it (SIGKILL: no chance to tidy up) once some runs are committed and before it is done.
  std::size_t before_kill = 0;
  for (int wait = 0; wait < 600 && before_kill < 3; ++wait) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (fs::exists(store_file(killed))) {
      try {
        before_kill = stored_records(killed).size();
      } catch (const Error&) {  // the schema is being created
      }
    }
  }
  ASSERT_EQ(::kill(static_cast<pid_t>(pid), SIGKILL), 0);
  while (::kill(static_cast<pid_t>(pid), 0) == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const std::size_t stored = stored_records(killed).size();
  ASSERT_GE(stored, 3u);
  ASSERT_LT(stored, 16u) << "the campaign ended before it was killed: the test proves nothing";

  const auto resumed = run_thetad(scratch_.path(), "campaign run " + file.string() + " --out " + killed.string() +
                                                       " --no-timing --resume --jobs 2");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_THAT(resumed.err, HasSubstr(std::to_string(stored) + " already stored"));
  const auto whole = run_thetad(scratch_.path(), "campaign run " + file.string() + " --out " +
                                                     (scratch_.path() / "whole").string() + " --no-timing --jobs 2");
  ASSERT_EQ(whole.status, 0) << whole.err;
  EXPECT_THAT(whole.out, HasSubstr("16 runs in shard 1/1, 16 flown now"));
  expect_same_runs(stored_records(scratch_.path() / "whole"), stored_records(killed));
}

TEST_F(CampaignCommand, TwoMpiRanksWriteTheDatabaseOfOneProcess) {
  const fs::path file = write_campaign(testing::small_campaign("mpi-test", 4, 5, "{grid: {gust_scale: [0, 2]}}"));
  const fs::path single = scratch_.path() / "single", ranks = scratch_.path() / "ranks";
  const auto one = run_thetad(scratch_.path(), "campaign run " + file.string() + " --out " + single.string() +
                                                   " --no-timing --jobs 1");
  ASSERT_EQ(one.status, 0) << one.err;
  // Loopback only, as root in a container: the settings docs/campaigns.md gives for a laptop.
  const std::string mpi_environment =
      "OMPI_MCA_btl=self,vader OMPI_MCA_pml=ob1 OMPI_MCA_oob_tcp_if_include=lo OMPI_MCA_rmaps_base_oversubscribe=1 "
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1";
  const std::string command = mpi_environment + " " + std::string(THETAD_MPIEXEC) + " -np 2 " + THETAD_BINARY +
                              " campaign run " + file.string() + " --out " + ranks.string() + " --no-timing >" +
                              (scratch_.path() / "mpi.out").string() + " 2>&1";
  const int status = std::system(command.c_str());
  const std::string output = testing::read_text(scratch_.path() / "mpi.out");
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
  EXPECT_THAT(output, HasSubstr("16 runs in shard 1/1, 16 flown now"));
  expect_same_runs(stored_records(single), stored_records(ranks));
}

TEST_F(CampaignCommand, TheReportWritesTablesJsonAndFiguresOfA2dSweep) {
  const fs::path file = write_campaign(
      testing::small_campaign("report-test", 3, 2, "{grid: {uncertainty_scale: [0, 2], gust_scale: [0, 3]}}"));
  const fs::path out = scratch_.path() / "out";
  ASSERT_EQ(run_thetad(scratch_.path(), "campaign run " + file.string() + " --out " + out.string()).status, 0);
  const auto report = run_thetad(scratch_.path(), "campaign report " + out.string() + " --seed 4");
  ASSERT_EQ(report.status, 0) << report.out << report.err;
  const fs::path folder = out / "report";
  for (const char* figure : {"cdf_rms_error.png", "cdf_cost.png", "completion.png", "envelope_lqr.png", "envelope_td.png",
                             "paired_violins.png"})
    EXPECT_GT(fs::file_size(folder / figure), 1000u) << figure;
  const std::string markdown = testing::read_text(folder / "report.md");
  EXPECT_THAT(markdown, HasSubstr("| uncertainty_scale=2, gust_scale=3 | td | 3/3 | 100.0 % (43.9-100.0 %) |"));
  EXPECT_THAT(markdown, HasSubstr("lqr's RMS 3-D position error is"));
  const auto json = nlohmann::json::parse(testing::read_text(folder / "report.json"));
  EXPECT_EQ(json.at("runs_stored"), 24);
  EXPECT_EQ(json.at("controllers").size(), 8u);  // 4 cells x 2 controllers
  EXPECT_EQ(json.at("paired").size(), 16u);      // 4 cells x 4 metrics
  EXPECT_EQ(json.at("controllers")[0].at("information"), "none");
  EXPECT_EQ(json.at("controllers")[0].at("label"), "lqr");
  EXPECT_EQ(json.at("paired")[0].at("metric"), "rms_error_m");
  EXPECT_EQ(json.at("statistics").at("bootstrap").at("seed"), 4);
  ASSERT_EQ(json.at("provenance").size(), 1u);  // one scenario
  EXPECT_EQ(json.at("provenance")[0].at("scenario").at("name"), "scenario-1");
  EXPECT_EQ(json.at("provenance")[0].at("scenario").at("sha256").get<std::string>().size(), 64u);
  EXPECT_FALSE(json.at("provenance")[0].at("git_revision").get<std::string>().empty());
  // Seeded: the same report twice.
  ASSERT_EQ(run_thetad(scratch_.path(), "campaign report " + out.string() + " --seed 4 --out " +
                                            (scratch_.path() / "again").string()).status, 0);
  EXPECT_EQ(testing::read_text(scratch_.path() / "again" / "report.md"), markdown);
}

TEST_F(CampaignCommand, ABadCampaignFileIsOneLineNamingFileLineAndField) {
  const fs::path file = write_campaign("campaign: bad\nscenarios: [scenario-1]\ncontrollers: [{controller: lqr}]\n"
                                       "draws: {count: 2}\nsweep: {grid: {gust_scale: [1, -1]}}\n");
  const auto result = run_thetad(scratch_.path(), "campaign run " + file.string() + " --out " +
                                                      (scratch_.path() / "out").string());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr(file.string() + ":5:32: field 'sweep.grid.gust_scale[1]'"));
  EXPECT_FALSE(fs::exists(scratch_.path() / "out"));
}

TEST_F(CampaignCommand, ADryRunCountsTheRunsAndEstimatesTheCost) {
  const fs::path file = write_campaign(R"(campaign: dry
scenarios: [scenario-1]
controllers: [{controller: lqr}]
draws: {count: 10}
sweep: {grid: {uncertainty_scale: [0, 1, 2]}}
)");
  const auto result = run_thetad(scratch_.path(), "campaign run " + file.string() + " --dry-run --pilot 0.1 --jobs 2");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("1 scenario(s) x 1 controller(s) x 3 cell(s) x 10 draws = 30 runs"));
  EXPECT_THAT(result.out, HasSubstr("pilot lqr"));
  EXPECT_THAT(result.out, HasSubstr("core-hours"));
}

}  // namespace
}  // namespace thetad
