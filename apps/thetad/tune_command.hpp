#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "apps/thetad/run_command.hpp"

namespace thetad::app {

struct TuneArguments {
  FlightOptions flight;             // the SDRE and θ–D blocks of --settings start the fit; --out required
  std::string objective = "sigma";  // sigma | entries | closed-loop
  std::string controller = "theta-d";    // the controller tuned (its settings block in --settings)
  std::optional<std::string> parameters;  // series | weights; unset: series for theta-d, else weights
  double weight_bounds = 2.0;             // weights: each log10 factor in [-bound, bound]
  int terms = 3;                    // N of the θ–D series
  std::optional<std::string> algorithm;  // unset: LN_BOBYQA; LN_COBYLA for closed-loop (see docs/tuning.md)
  std::optional<int> max_evaluations;  // unset: 1500 for sigma and entries, 40 for closed-loop
  double max_seconds = 0.0;            // 0: no time budget
  // sigma, entries: the SDRE record
  std::filesystem::path record;     // reused when it exists, else written there
  int every = 10;                   // keep every N-th 1 kHz controller sample: 100 Hz
  bool relative = false;            // sigma
  double entry_floor = 1e-3;        // entries
  // closed-loop
  std::string metric = "cost";
  int draws = 5;                    // training draws: seeds S … S+draws−1 (S: the flight's seed)
  // validation
  int holdout_draws = 10;
  std::optional<std::uint64_t> holdout_seed;  // first held-out seed; unset: right after the training seeds
  std::vector<double> k_bounds{0.0, 1.5};
  std::vector<double> l_bounds{0.01, 20.0};
  std::filesystem::path holdout;    // empty: the other paper scenario when tuning on one of them
  bool no_validation = false;
  int threads = 2;
};
CLI::App* add_tune_command(CLI::App& app, TuneArguments& arguments);

// thetad tune: fit θ–D's k_i, l_i by the chosen objective (the paper's σ_max match on an SDRE
// record, the per-entry match, or the closed loop over training draws), or any controller's
// weights by the closed loop, then validate default against tuned on held-out draws of the tuning
// scenario and of a held-out scenario. Writes <out>/CONTROLLER-tuned.yaml (a --settings file for
// thetad run), <out>/tuning.json and, for the sigma objective, <out>/sigma-curves.csv; key=value
// lines on stdout. Every input is checked before anything is flown or written.
int run_tune(const TuneArguments& arguments);

}  // namespace thetad::app
