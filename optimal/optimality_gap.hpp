#pragma once

#include <string>
#include <vector>

#include "experiment/flight.hpp"
#include "experiment/run_result.hpp"
#include "optimal/optimal_control.hpp"

namespace thetad {

struct OptimalityOptions {
  double control_interval = 0.05;  // s: the input is held this long in the transcription (a multiple of T_c)
  std::string warm_start;          // the label of the flight to start from; empty: the cheapest completed one
  OptimalControlSettings solver;
};

// How far each controller's flight is from the optimum of the same problem: the flights, the
// optimal control problem of the flight's scenario over their duration, its solution, and the
// optimum as a run (label "optimal": its log, summary and the transcription in its settings).
struct OptimalityGap {
  std::vector<RunResult> flights;
  OptimalControlProblem problem;
  OptimalControlSolution solution;
  std::string warm_start;  // the label the solve started from
  RunResult optimum;

  // 100 (J_flight − J*) / J*: how much more the flight costs than the optimum, in percent.
  double gap_percent(const RunResult& flight) const;
};

// Flies every controller through `flight` over its duration, then solves the optimal control
// problem on the controllers' model (the helicopter: J priced as simulate() prices it) from the
// warm-start flight by multiple shooting (solve_optimal_control). The flight must be ideal (no
// uncertainty, noise or wind: the optimum is of the nominal plant), without actuator limits, and
// log every sample; its duration must be a whole number of control intervals. Throws
// thetad::Error naming what is wrong before anything flies, and when no flight completed to warm
// start from (or the named one did not).
OptimalityGap optimality_gap(const Flight& flight, std::vector<PreparedController>& controllers,
                             const OptimalityOptions& options, Progress* progress = nullptr);

}  // namespace thetad
