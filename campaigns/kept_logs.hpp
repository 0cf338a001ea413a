#pragma once

#include <cstdint>
#include <filesystem>

#include "campaigns/run_plan.hpp"

namespace thetad {

// The runs of a campaign that keep their full log (--keep-logs K), and where. Kept: the first K
// draws of every cell, scenario and controller, chosen from the run plan alone (the same runs for
// any --jobs, rank count or shard), and every run that diverged or failed. Run i's files are
// <out>/logs/<i>/<label>.csv and <label>.json, what `thetad run --out` writes: a row's run_index
// names its folder.
struct KeptLogs {
  int draws = 0;
  std::filesystem::path out;  // the campaign's output folder

  bool keeps(const PlannedRun& run) const { return run.draw < draws; }
  std::filesystem::path run_folder(std::int64_t index) const;
};

}  // namespace thetad
