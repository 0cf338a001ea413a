#pragma once

// Every tuning result, whatever its objective, is judged on draws it never saw: the default and
// the tuned controller fly the same held-out draws (seeds disjoint from the training draws), and
// the per-draw differences tuned − default of the cost J, of J_dev (where the runs have it) and of
// the RMS error are summarised by their median with a bootstrap interval (paired_bootstrap).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/sim/simulator.hpp"
#include "tuning/closed_loop.hpp"
#include "tuning/paired_bootstrap.hpp"

namespace thetad::tuning {

struct DrawSeeds {
  std::vector<std::uint64_t> training, held_out;
};

// `training` consecutive seeds from `training_first` and `held_out` from `held_out_first`.
// Throws thetad::Error, naming a shared seed, when the two sets overlap, and for a negative count.
DrawSeeds draw_seeds(std::uint64_t training_first, int training, std::uint64_t held_out_first, int held_out);

// The paired comparison of one metric over the draws both controllers completed.
struct PairedComparison {
  Metric metric = Metric::cost;
  double default_median = 0.0, tuned_median = 0.0;  // over the compared pairs
  BootstrapMedian difference;  // of tuned − default, per draw
};

struct HeldOutValidation {
  std::string scenario;
  std::vector<std::uint64_t> seeds;
  std::vector<sim::RunSummary> default_runs, tuned_runs;  // per seed
  int resamples = 0;
  std::uint64_t bootstrap_seed = 0;
  PairedComparison cost, rms_error;
  std::optional<PairedComparison> cost_dev;  // where the runs have J_dev

  int pairs() const { return cost.difference.count; }
  // Draws that diverged or failed (docs/glossary.md, "How a run ended").
  int default_not_completed() const;
  int tuned_not_completed() const;
};

// Flies the default (the controller as given) and the tuned one (at `tuned`, a point of the
// parameterization's box) on every held-out seed and compares them. Throws thetad::Error when no
// seed is given or no draw was completed by both.
HeldOutValidation validate_held_out(DrawFlights& flights, const Eigen::VectorXd& tuned,
                                    const std::vector<std::uint64_t>& seeds, std::uint64_t bootstrap_seed,
                                    int resamples = 2000);

}  // namespace thetad::tuning
