#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "experiment/progress.hpp"
#include "experiment/run_result.hpp"

namespace thetad {

struct Replay {
  RunResult result;                      // the run flown again
  std::vector<std::string> differences;  // summary fields that differ from the recorded ones; empty: agrees
};

// Flies again exactly the run a result file describes, from what it says alone: the scenario as
// it recorded it (results of format_version 1: the scenario file, which must still have the
// recorded SHA-256), or the plant and its initial state, the controller with its recorded
// settings, the seed, dt, duration, logging and disturbance switches. Compares every summary figure but the
// wall-clock ones, under the current names (with_current_names); a figure that the file's earlier
// format_version did not record is not compared. Throws thetad::Error when the file cannot be
// replayed (and says why).
Replay replay(const std::filesystem::path& result_file, Progress* progress = nullptr);

}  // namespace thetad
