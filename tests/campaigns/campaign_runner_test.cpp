#include "campaigns/campaign_runner.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campaigns/campaign_merge.hpp"
#include "campaigns/run_plan.hpp"
#include "core/error.hpp"
#include "experiment/run_files.hpp"
#include "tests/campaigns/campaign_testing.hpp"
#include "tests/scratch_directory.hpp"

namespace thetad {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::expect_same_runs;
using testing::stored_records;

// Two cells x two controllers x three draws: twelve short runs.
const std::string kCampaign = testing::small_campaign("runner-test", 3, 11, "{grid: {uncertainty_scale: [0.5, 2]}}");

class CampaignRunner : public ::testing::Test {
 protected:
  Campaign campaign(const std::string& text = kCampaign) const {
    const fs::path file = scratch_.path() / "campaign.yaml";
    std::ofstream(file) << text;
    return load_campaign(file);
  }
  CampaignOptions options(const std::string& out, int jobs) const {
    CampaignOptions o;
    o.out = scratch_.path() / out;
    o.jobs = jobs;
    o.timing = false;
    o.progress = Progress::Mode::quiet;
    return o;
  }
  testing::ScratchDirectory scratch_{"campaign_runner_test"};
};

TEST_F(CampaignRunner, TheDatabaseIsTheSameForAnyNumberOfWorkersAndShards) {
  const Campaign c = campaign();
  const CampaignOutcome one = run_campaign(c, options("one", 1));
  EXPECT_EQ(one.runs, 12);
  EXPECT_EQ(one.flown, 12);
  const std::vector<RunRecord> expected = stored_records(options("one", 1).out);
  ASSERT_EQ(expected.size(), 12u);
  // Paired draws: the controllers of one draw fly the same seed, the same parameter draw.
  EXPECT_EQ(expected[0].seed, expected[1].seed);
  EXPECT_EQ(expected[0].seed, draw_seed(11, 0));
  EXPECT_EQ(expected[0].label, "lqr");
  EXPECT_EQ(expected[1].label, "td");
  EXPECT_EQ(expected[1].controller, "theta-d");
  EXPECT_EQ(expected[6].factors, (FactorValues{{"uncertainty_scale", 2.0}, {"duration_s", 0.2}}));
  EXPECT_NE(expected[0].metrics[8], expected[6].metrics[8]);  // the cells differ in cost
  EXPECT_TRUE(std::isfinite(expected[0].metrics[9]));          // J_dev: the helicopter has trims
  EXPECT_EQ(expected[0].information, "none");

  run_campaign(c, options("two", 2));
  expect_same_runs(expected, stored_records(options("two", 2).out));

  for (int k = 1; k <= 3; ++k) {
    CampaignOptions part = options("shard" + std::to_string(k), 2);
    part.shard = Shard{k, 3};
    EXPECT_EQ(run_campaign(c, part).runs, 4);
  }
  merge_shards({scratch_.path() / "shard2", scratch_.path() / "shard1", scratch_.path() / "shard3"},
               scratch_.path() / "merged");
  expect_same_runs(expected, stored_records(scratch_.path() / "merged"));
  const CampaignStore merged(store_file(scratch_.path() / "merged"));
  EXPECT_EQ(merged.meta("shard"), "1/1");
  EXPECT_EQ(merged.meta("campaign_sha256"), c.sha256);
}

TEST_F(CampaignRunner, ResumeFliesOnlyWhatIsMissingAndRefusesAnotherCampaign) {
  const Campaign c = campaign();
  CampaignOptions first = options("resumed", 1);
  first.shard = Shard{1, 2};
  run_campaign(c, first);
  first.resume = true;
  EXPECT_EQ(run_campaign(c, first).flown, 0);  // complete: nothing to fly

  CampaignOptions again = options("resumed", 1);
  try {
    run_campaign(c, again);
    FAIL() << "an existing database was overwritten";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("exists: pass --resume"));
  }
  again.resume = true;
  again.shard = Shard{2, 2};
  EXPECT_THROW(run_campaign(c, again), Error);  // another shard
  again.shard = Shard{1, 2};
  const Campaign other = campaign(kCampaign + "    # another campaign file\n");
  try {
    run_campaign(other, again);
    FAIL() << "resumed another campaign";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("holds another campaign"));
  }
}

// What a database of an earlier format_version looks like to this thetad: its meta says so
// (version 1 had no format_version at all).
void set_format_version(const fs::path& database, const std::string& version) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(database.c_str(), &db), SQLITE_OK);
  const std::string sql = version.empty() ? "DELETE FROM meta WHERE key = 'format_version'"
                                          : "INSERT OR REPLACE INTO meta (key, value) VALUES ('format_version', '" +
                                                version + "')";
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
}

TEST_F(CampaignRunner, ResumeAndMergeRefuseADatabaseOfAnEarlierFormatVersionSayingWhatToDo) {
  const Campaign c = campaign();
  CampaignOptions first = options("earlier", 1);
  first.shard = Shard{1, 2};
  run_campaign(c, first);
  first.resume = true;
  for (const std::string version : {"", "4"}) {
    set_format_version(store_file(first.out), version);
    try {
      run_campaign(c, first);
      FAIL() << "resumed a database of an earlier format";
    } catch (const Error& error) {
      EXPECT_THAT(error.what(), HasSubstr(store_file(first.out).string() + ": a campaign database of format_version " +
                                          (version.empty() ? "1" : version)));
      EXPECT_THAT(error.what(), HasSubstr("cannot resume it"));
      EXPECT_THAT(error.what(), HasSubstr("`thetad campaign report` still reads it"));
      EXPECT_THAT(error.what(), HasSubstr("run the campaign anew"));
    }
  }
  // The report's check opens it; merging it is refused like resuming.
  EXPECT_EQ(CampaignStore(store_file(first.out)).format_version(), 4);
  CampaignOptions second = options("later", 1);
  second.shard = Shard{2, 2};
  run_campaign(c, second);
  try {
    merge_shards({first.out, second.out}, scratch_.path() / "merged");
    FAIL() << "merged a database of an earlier format";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("format_version 4"));
    EXPECT_THAT(error.what(), HasSubstr("cannot merge it"));
  }
  EXPECT_FALSE(fs::exists(scratch_.path() / "merged"));
  // A database of a newer thetad is refused by every reader, saying so.
  set_format_version(store_file(first.out), "8");
  try {
    CampaignStore newer(store_file(first.out));
    FAIL() << "opened a database of a newer format";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("written by a newer thetad (format_version 8; this one reads up to 7)"));
  }
}

TEST_F(CampaignRunner, MergeRefusesShardsOfAnotherCampaignAMissingOrRepeatedShard) {
  const Campaign c = campaign();
  const Campaign other = campaign(kCampaign + "# another campaign\n");
  CampaignOptions part = options("a1", 2);
  part.shard = Shard{1, 2};
  run_campaign(c, part);
  part.out = scratch_.path() / "b2";
  part.shard = Shard{2, 2};
  run_campaign(other, part);
  const auto merge_error = [&](const std::vector<fs::path>& shards) {
    try {
      merge_shards(shards, scratch_.path() / "merged");
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(merge_error({scratch_.path() / "a1", scratch_.path() / "b2"}), HasSubstr("holds another campaign"));
  EXPECT_THAT(merge_error({scratch_.path() / "a1"}), HasSubstr("shard 2/2 is missing"));
  EXPECT_THAT(merge_error({scratch_.path() / "a1", scratch_.path() / "a1"}), HasSubstr("given twice"));
  EXPECT_FALSE(fs::exists(store_file(scratch_.path() / "merged")));
}

// The files under <out>/logs, relative to it, with their bytes.
std::map<std::string, std::string> kept_files(const fs::path& out) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(out / "logs")) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    files[fs::relative(entry.path(), out).string()] = {std::istreambuf_iterator<char>(in), {}};
  }
  return files;
}

TEST_F(CampaignRunner, KeptLogsAreTheFirstDrawsOfEveryCellAndEveryDivergedRunWhateverTheWorkers) {
  // Cell 1 starts rolled past the divergence limit: each of its runs diverges at once.
  const Campaign c = campaign(testing::small_campaign("kept-logs", 3, 5,
                                                      "{list: [{initial_offset_roll_deg: 0}, {initial_offset_roll_deg: 90}]}"));
  CampaignOptions one = options("one", 1);
  one.keep_logs = 1;
  run_campaign(c, one);
  const std::vector<RunRecord> records = stored_records(one.out);
  ASSERT_EQ(records.size(), 12u);
  std::set<std::string> expected;
  for (const RunRecord& record : records) {
    EXPECT_EQ(record.completed(), record.cell == 0) << record.index;
    if (record.draw == 0 || !record.completed()) {
      for (const char* extension : {".csv", ".json"})
        expected.insert((fs::path("logs") / std::to_string(record.index) / (record.label + extension)).string());
    }
  }
  const std::map<std::string, std::string> kept = kept_files(one.out);
  std::set<std::string> names;
  for (const auto& [name, bytes] : kept) names.insert(name);
  EXPECT_EQ(names, expected);
  // A kept log is the whole flight, and its result the row's: 0.2 s at 1 kHz.
  const StoredRun first = read_run_files(one.out / "logs" / "0" / (records[0].label + ".json"));
  EXPECT_EQ(first.result.at("controller_samples").get<std::int64_t>(), records[0].controller_samples);
  EXPECT_EQ(first.result.at("seed").get<std::uint64_t>(), records[0].seed);
  EXPECT_EQ(std::count(kept.at("logs/0/" + records[0].label + ".csv").begin(),
                       kept.at("logs/0/" + records[0].label + ".csv").end(), '\n'),
            1 + 200);
  const StoredRun diverged = read_run_files(one.out / "logs" / "7" / (records[7].label + ".json"));
  EXPECT_EQ(diverged.result.at("status").get<std::string>(), "diverged");
  EXPECT_EQ(diverged.result.at("reason").get<std::string>(), records[7].reason);

  // Which logs are kept depends on the plan alone: two workers, or three shards, keep the same files.
  CampaignOptions two = options("two", 2);
  two.keep_logs = 1;
  run_campaign(c, two);
  EXPECT_EQ(kept_files(two.out), kept);
  std::map<std::string, std::string> sharded;
  for (int k = 1; k <= 3; ++k) {
    CampaignOptions part = options("shard" + std::to_string(k), 1);
    part.shard = Shard{k, 3};
    part.keep_logs = 1;
    run_campaign(c, part);
    sharded.merge(kept_files(part.out));
  }
  EXPECT_EQ(sharded, kept);
  // Without --keep-logs, no log at all.
  run_campaign(c, options("none", 1));
  EXPECT_FALSE(fs::exists(scratch_.path() / "none" / "logs"));
}

TEST_F(CampaignRunner, ABadCellFailsBeforeAnythingFlies) {
  const Campaign c = campaign(R"(campaign: bad-dt
scenarios: [scenario-1]
controllers: [{controller: lqr}]
draws: {count: 2}
sweep: {grid: {dt_s: [0.001, 0.0003]}}
)");
  try {
    run_campaign(c, options("bad", 1));
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("sweep cell 1 (dt_s=0.000300)"));
    EXPECT_THAT(error.what(), HasSubstr("does not divide the controller period"));
  }
  EXPECT_FALSE(fs::exists(store_file(scratch_.path() / "bad")));
}

}  // namespace
}  // namespace thetad
