#pragma once

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/run_files.hpp"
#include "optimal/optimality_gap.hpp"

namespace thetad {

inline constexpr const char* kOptimalityFormat = "thetad-optimality-3";
// optimality.json's "format_version" within that format:
//   1 (no "format_version"): controllers[].status is the status text ("diverged at 1.234 s").
//   2: controllers[].status is the bare status (completed, diverged, failed) with end_time_s beside
//      it, as in a run result (docs/glossary.md "How a run ended").
inline constexpr int kOptimalityFormatVersion = 2;

// Every run of a gap in the order its files are written and reported: the flights, then per
// optimum the optimum and, with bounds, the unbounded one.
std::vector<RunResult> optimality_runs(const OptimalityGap& gap);

// optimality.json (kOptimalityFormat; docs/optimality.md): the segment, the cost minimized, the
// bounds, per optimum its solves (Ipopt's status, iterations, largest defect, J and J_dev, result
// file), per controller its cost over the segment and its gaps. `files` are those of
// optimality_runs(gap), in order; empty: nothing was written, and the solves name no file.
nlohmann::ordered_json optimality_json(const Flight& flight, const OptimalityGap& gap, const OptimalityOptions& options,
                                       const std::vector<RunFiles>& files);

// What `thetad optimal` writes into `out` (prepared by the caller, prepare_output_folder): the
// result files of optimality_runs(gap), comparison.json and optimality.json, the latter two
// removed first so that a failure leaves none of a previous run. Returns optimality.json's content.
nlohmann::ordered_json write_optimality(const Flight& flight, const OptimalityGap& gap, const OptimalityOptions& options,
                                        const std::filesystem::path& out);

// Whether every solve converged.
bool optimality_converged(const OptimalityGap& gap);
// Whether every unbounded optimum costs no more than its bounded one, within `relative`: the check
// that both solves found minima (dropping bounds cannot cost more).
bool unbounded_at_most_bounded(const OptimalityGap& gap, double relative = 1e-6);

}  // namespace thetad
