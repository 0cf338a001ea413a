#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/flight.hpp"
#include "experiment/run_files.hpp"
#include "experiment/run_result.hpp"

namespace thetad {

// The comparison table of several runs of one flight, one row per label: status, RMS position
// error per axis and in 3-D (rms_error_m), max position error per axis, effort, J_dev, cost J and
// the in-flight step time (with a note that it includes the simulation's noise: `thetad bench`
// measures the per-step cost).
std::string comparison_table(const std::vector<RunResult>& runs);

// comparison.json: the flight (scenario, seed, disturbances, provenance) and, per run in order,
// its label, controller and result file with the file's SHA-256 (the result file names its log
// the same way), so that a run written into the folder later is not taken for one of the compare.
nlohmann::ordered_json comparison_json(const Flight& flight, const std::vector<RunResult>& runs,
                                       const std::vector<RunFiles>& files);

}  // namespace thetad
