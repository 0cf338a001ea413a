#include "campaigns/run_plan.hpp"

#include <set>

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace thetad {
namespace {

Campaign shape(int cells, int scenarios, int controllers, int draws) {
  Campaign campaign;
  campaign.cells.resize(static_cast<std::size_t>(cells));
  campaign.scenarios.resize(static_cast<std::size_t>(scenarios));
  campaign.controllers.resize(static_cast<std::size_t>(controllers));
  campaign.draws = draws;
  campaign.base_seed = 42;
  return campaign;
}

TEST(RunPlan, TheDrawSeedDependsOnTheBaseSeedAndTheDrawOnly) {
  const Campaign campaign = shape(3, 2, 4, 5);
  std::set<std::uint64_t> seeds;
  for (std::int64_t i = 0; i < campaign.run_count(); ++i) {
    const PlannedRun run = planned_run(campaign, i);
    EXPECT_EQ(run.seed, draw_seed(42, run.draw)) << i;  // every cell, scenario and controller
    seeds.insert(run.seed);
  }
  EXPECT_EQ(seeds.size(), 5u);  // one per draw, all different
  EXPECT_NE(draw_seed(42, 0), draw_seed(43, 0));
  EXPECT_NE(draw_seed(42, 0), draw_seed(42, 1));
  EXPECT_EQ(draw_seed(42, 3), draw_seed(42, 3));
}

TEST(RunPlan, TheRunIndexOrdersCellsScenariosDrawsThenControllers) {
  const Campaign campaign = shape(3, 2, 4, 5);
  const PlannedRun run = planned_run(campaign, ((2 * 2 + 1) * 5 + 3) * 4 + 1);
  EXPECT_EQ(run.cell, 2);
  EXPECT_EQ(run.scenario, 1);
  EXPECT_EQ(run.draw, 3);
  EXPECT_EQ(run.controller, 1);
  EXPECT_THROW(planned_run(campaign, campaign.run_count()), Error);
  EXPECT_THROW(planned_run(campaign, -1), Error);
}

TEST(RunPlan, ShardsPartitionTheRuns) {
  for (int n = 1; n <= 5; ++n) {
    for (std::int64_t i = 0; i < 37; ++i) {
      int holders = 0;
      for (int k = 1; k <= n; ++k) holders += Shard{k, n}.holds(i) ? 1 : 0;
      EXPECT_EQ(holders, 1) << i << " in " << n << " shards";
    }
  }
  const Shard shard = parse_shard("3/8");
  EXPECT_EQ(shard.k, 3);
  EXPECT_EQ(shard.n, 8);
  EXPECT_EQ(shard.text(), "3/8");
  for (const char* bad : {"0/4", "5/4", "1/0", "1", "a/b", "1/2x", "/2", "-1/2"}) EXPECT_THROW(parse_shard(bad), Error) << bad;
}

}  // namespace
}  // namespace thetad
