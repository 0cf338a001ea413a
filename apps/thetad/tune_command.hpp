#pragma once

#include <CLI/CLI.hpp>

#include "apps/thetad/run_command.hpp"
#include "tuning/tune_run.hpp"

namespace thetad::app {

struct TuneArguments {
  FlightOptions flight;       // scenario, settings, run controls and out (required) of tune
  tuning::TuneOptions tune;   // the rest; its scenario, settings, controls and out come from `flight`
};
CLI::App* add_tune_command(CLI::App& app, TuneArguments& arguments);

// thetad tune: fit θ–D's k_i, l_i by the chosen objective (the paper's σ_max match on an SDRE
// record, the per-entry match, or the closed loop over training draws), or any controller's
// weights by the closed loop, then validate default against tuned on held-out draws of the tuning
// scenario and of a held-out scenario (tuning::tune, which writes the files); key=value lines on
// stdout.
int run_tune(const TuneArguments& arguments);

}  // namespace thetad::app
