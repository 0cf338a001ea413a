#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "apps/thetad/run_command.hpp"
#include "experiment/step_timing.hpp"

namespace thetad::app {

struct BenchArguments {
  FlightOptions flight;                  // --scenario (default scenario-1), --settings, --seed, ...; --out: a JSON file
  std::vector<std::string> controllers;  // specs, as for compare
  StepTimingOptions timing;
};
CLI::App* add_bench_command(CLI::App& app, BenchArguments& arguments);

// thetad bench: the per-step cost of each controller on states recorded along a flight of the
// scenario (flown by the first controller), outside the simulation loop, pinned, warmed up, with
// interleaved repetitions; a table on stdout and the figures as JSON (--out).
int run_bench(const BenchArguments& arguments);

}  // namespace thetad::app
