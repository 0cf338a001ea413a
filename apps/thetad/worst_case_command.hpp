#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "apps/thetad/run_command.hpp"
#include "tuning/worst_case.hpp"

namespace thetad::app {

struct WorstCaseArguments {
  FlightOptions flight;
  std::vector<std::string> controllers;
  std::string metric = "rms_error_m";
  tuning::WorstCaseOptions options;
};
CLI::App* add_worst_case_command(CLI::App& app, WorstCaseArguments& arguments);

// thetad worst-case: each controller's worst case of Table 1's parameter bounds on a scenario
// (tuning/worst_case); a table on stdout, <out>/worst_case.json and, per controller,
// <out>/<label>-worst-case.yaml, the scenario that flies it again. Exit code 0.
int run_worst_case(const WorstCaseArguments& arguments);

}  // namespace thetad::app
