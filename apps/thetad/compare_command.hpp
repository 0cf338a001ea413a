#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "apps/thetad/run_command.hpp"

namespace thetad::app {

struct CompareArguments {
  FlightOptions flight;
  std::vector<std::string> controllers;  // NAME, LABEL=NAME, NAME:FILE or LABEL=NAME:FILE
  std::filesystem::path controllers_file;  // or a YAML list of {label, controller, settings}
};
CLI::App* add_compare_command(CLI::App& app, CompareArguments& arguments);

// thetad compare: every controller on the same scenario and seed (same perturbed plant, same noise
// and gust sequence), one after the other; <out>/<label>.csv and .json per run, a table on stdout
// and <out>/comparison.json (removed first, written last: it exists only for a finished compare).
// Every controller is built before the first flight, so a bad name or settings block fails before
// anything is written. Exit code 3 when any run diverged.
int run_compare(const CompareArguments& arguments);

}  // namespace thetad::app
