#pragma once

// A whole tuning run, for every front end (`thetad tune`, Python's thetad.tune): the objective's
// search (the SDRE record flown or reused for sigma and entries, the draws for the closed loop),
// the tuned settings file, the held-out validation and tuning.json (docs/tuning.md).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "experiment/progress.hpp"
#include "settings/run_controls.hpp"
#include "tuning/tuning_report.hpp"

namespace thetad::tuning {

// The command line's arguments of `thetad tune`, as plain data.
struct TuneOptions {
  std::string scenario;            // a file, or the name of a shipped scenario
  std::filesystem::path settings;  // its SDRE and tuned controller's blocks start the fit; empty: defaults
  RunControls controls;            // every flight but the SDRE record's is summary-only
  std::filesystem::path out;       // created, and checked before anything flies
  std::string objective = "sigma";         // sigma | entries | closed-loop (parse_objective)
  std::string controller = "theta-d";      // the controller tuned (its settings block is the start)
  std::optional<std::string> parameters;   // series | weights; unset: series for theta-d, else weights
  double weight_bounds = 2.0;              // weights: each log10 factor in [-bound, bound]
  int terms = 3;                           // N of the θ–D series
  std::optional<std::string> algorithm;    // unset: LN_BOBYQA; LN_COBYLA for closed-loop (see docs/tuning.md)
  std::optional<int> max_evaluations;      // unset: 1500 for sigma and entries, 40 for closed-loop
  double max_seconds = 0.0;                // 0: no time budget
  // sigma, entries: the SDRE record
  std::filesystem::path record;  // reused when it exists, else written there; empty: <out>/sdre-record.csv, re-flown
  int every = 10;                // keep every N-th 1 kHz controller sample: 100 Hz
  bool relative = false;         // sigma: fit (σ_θ–D − σ_SDRE) / σ_SDRE
  double entry_floor = 1e-3;     // entries: see entry_fit.hpp
  // closed-loop
  std::string metric = "cost";   // cost | rms_error_m | cost_dev (parse_metric)
  int draws = 5;                 // training draws: seeds S … S+draws−1 (S: the flight's seed)
  // validation
  bool validation = true;
  int holdout_draws = 10;
  std::optional<std::uint64_t> holdout_seed;  // first held-out seed; unset: right after the training seeds
  std::string holdout;  // a held-out scenario; empty: the other paper scenario when tuning on one of them
  std::vector<double> k_bounds{0.0, 1.5};     // lower, upper of every k_i
  std::vector<double> l_bounds{0.01, 20.0};   // lower, upper of every l_i
  int threads = 2;               // of the fit and of the flights
};

// Tunes as `options` say and writes <out>/CONTROLLER-tuned.yaml (a --settings file that flies the
// tuned controller), <out>/tuning.json (to_json of the report) and, for the sigma objective,
// <out>/sigma-curves.csv, all once the validation is done (report.files, in that order); the SDRE
// record is written as soon as it is flown (`record`, else <out>/sdre-record.csv). Every input is
// checked before anything flies or is written; thetad::Error says what is wrong.
// `progress` shows each task (the record's flight, the search, each validation); `observe`, when
// given, is called with the simulated time of the draws' flights on the calling thread. What either
// throws (Progress's observer, observe: a front end's Ctrl-C) stops the run and propagates out of
// tune(); none of the three files is then written.
TuningReport tune(const TuneOptions& options, Progress* progress = nullptr,
                  const std::function<void(double t)>& observe = {});

}  // namespace thetad::tuning
