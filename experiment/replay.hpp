#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "experiment/progress.hpp"
#include "experiment/run_result.hpp"

namespace thetad {

// A replay agrees with its recording when every figure is within this relative difference of the
// recorded one. The same build on the same machine replays bit for bit; another CPU or another
// build of libm or LAPACK rounds some operations differently in the last bit (glibc picks its sin,
// exp, pow for the CPU), which a flight carries to ~1e-15 relative in its figures. An edited
// figure, another seed or another setting is many orders beyond.
inline constexpr double kReplayTolerance = 1e-9;

struct Replay {
  RunResult result;                      // the run flown again
  // Summary fields beyond kReplayTolerance of the recorded ones, saying both; empty: agrees.
  std::vector<std::string> differences;
  // The largest relative difference of the fields within the tolerance: 0 when bit for bit.
  double largest_difference = 0.0;
};

// Flies again exactly the run a result file describes, from what it says alone: the scenario as
// it recorded it (results of format_version 1: the scenario file, which must still have the
// recorded SHA-256), or the plant and its initial state, the controller with its recorded
// settings, the seed, dt, duration, logging and disturbance switches. Compares every summary figure but the
// wall-clock ones, under the current names (with_current_names), to kReplayTolerance; a figure that
// the file's earlier format_version did not record is not compared. Throws thetad::Error when the file cannot be
// replayed (and says why).
Replay replay(const std::filesystem::path& result_file, Progress* progress = nullptr);

}  // namespace thetad
