#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "campaigns/campaign.hpp"
#include "campaigns/run_plan.hpp"
#include "experiment/progress.hpp"

namespace thetad {

struct CampaignOptions {
  std::filesystem::path out;  // the folder of campaign.sqlite
  Shard shard;                // 1/1: the whole campaign
  int jobs = 0;               // worker threads; 0: every core (one per rank under mpirun)
  bool resume = false;        // continue the database in `out`, skipping the runs it holds
  bool timing = true;         // false: no wall-clock figure (--no-timing)
  // --keep-logs K: the full logs of the first K draws of every cell and of every run that did not
  // complete, under out/logs (KeptLogs); none without.
  std::optional<int> keep_logs;
  Progress::Mode progress = Progress::Mode::lines;
  ProgressObserver observer;  // sees the runs stored (CampaignProgress); what it throws stops the campaign
};

struct CampaignOutcome {
  std::int64_t runs = 0;           // of the shard
  std::int64_t flown = 0;          // by this invocation
  std::int64_t not_completed = 0;  // of those flown: diverged or failed (docs/glossary.md)
  bool writer = true;              // false on MPI ranks other than 0 (they print nothing)
};

// Flies every run of the shard that `out` does not hold yet and stores it (CampaignStore). Worker
// threads take the next run index as they finish (dynamic scheduling), and the calling thread is
// the one writer. Under mpirun (MpiSession) rank 0 also hands out run indices to the other ranks.
// The stored rows depend on the run indices alone: the same for any --jobs, rank count or sharding.
CampaignOutcome run_campaign(const Campaign& campaign, const CampaignOptions& options);

}  // namespace thetad
