#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "apps/thetad/run_command.hpp"

namespace thetad::app {

struct DisturbancesArguments {
  FlightOptions flight;
  std::vector<std::string> controllers;
  int jobs = 0;  // 0: every core
};
CLI::App* add_disturbances_command(CLI::App& app, DisturbancesArguments& arguments);

// thetad disturbances: the scenario flown with each of its disturbance sources alone, all, none and
// all but one (experiment/disturbance_effects), every controller on the same seed; a table per
// controller on stdout and <out>/disturbances.json. Exit code 0 (a flight that did not complete is
// a result of the study, shown in the table).
int run_disturbances(const DisturbancesArguments& arguments);

}  // namespace thetad::app
