#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "experiment/controller_spec.hpp"

namespace thetad::app {

struct OptimalArguments {
  std::string scenario;
  std::string cost = "j-dev";
  bool actuator_limits = false;
  double start = 0.0;
  double horizon = 0.0;
  double control_interval = 0.05;
  std::vector<std::string> controllers{kAllControllers};
  std::filesystem::path settings;
  std::string warm_start;
  int max_iterations = 1000;
  double tolerance = 1e-6;
  bool no_timing = false;
  bool quiet = false;
  std::filesystem::path out;
};
CLI::App* add_optimal_command(CLI::App& app, OptimalArguments& arguments);

// thetad optimal: the controllers flown ideal (actuator limits on request) over `start` + `horizon`
// seconds of a scenario, the optimal control problem of the last `horizon` seconds with their cost
// (J_dev or J) solved (optimal/optimality_gap): from t = 0 once, from the cheapest flight; from
// mid-flight once per flight, from its state; with limits, bounded and then unbounded. A table of
// each cost over the segment, its optimum and the gap on stdout; <out>/<label>.csv and .json per
// controller and per optimum, <out>/comparison.json (so that `thetad plot` draws them together)
// and <out>/optimality.json (optimal/optimality_report.hpp). Exit code 0 when Ipopt converged on
// every solve and no unbounded optimum costs more than its bounded one, 3 otherwise.
int run_optimal(const OptimalArguments& arguments);

}  // namespace thetad::app
