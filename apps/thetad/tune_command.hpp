#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "apps/thetad/run_command.hpp"

namespace thetad::app {

struct TuneArguments {
  FlightOptions flight;             // the SDRE and θ–D blocks of --settings start the fit; --out required
  int terms = 3;                    // N of the θ–D series
  std::string algorithm = "LN_BOBYQA";
  std::filesystem::path record;     // reused when it exists, else written there
  int every = 10;                   // keep every N-th 1 kHz controller sample: 100 Hz
  bool relative = false;
  std::vector<double> k_bounds{0.0, 1.5};
  std::vector<double> l_bounds{0.01, 20.0};
  std::filesystem::path holdout;    // empty: the other paper scenario when tuning on one of them
  bool no_validation = false;
  int threads = 2;
};
CLI::App* add_tune_command(CLI::App& app, TuneArguments& arguments);

// thetad tune: record an SDRE flight (or reuse --record), fit k_i, l_i (spec §7.5), validate on
// the tuning and the held-out scenario. Writes <out>/theta-d-tuned.yaml (a --settings file for
// thetad run), <out>/sigma-curves.csv and <out>/tuning.json; key=value lines on stdout. Every input
// is checked before anything is flown or written.
int run_tune(const TuneArguments& arguments);

}  // namespace thetad::app
