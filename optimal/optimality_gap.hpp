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

  // 100 (J_flight − J*) / J*, J* as the run metrics sum the optimum's samples (the flights' way):
  // how much more the flight costs than the optimum, in percent.
  double gap_percent(const RunResult& flight) const;
};

// The optimal control problem of `flight`'s scenario over its duration, priced as simulate()
// prices J, on the controllers' model. Throws thetad::Error when the flight is not ideal, has
// actuator limits, does not log every sample, or its duration is not a whole number of control
// intervals (nothing needs to fly to find out).
OptimalControlProblem optimality_problem(const Flight& flight, const OptimalityOptions& options);

// Flies every controller through `flight` over its duration, then solves the optimal control
// problem (optimality_problem) from the warm-start flight by multiple shooting
// (solve_optimal_control). Throws thetad::Error naming what is wrong before anything flies, and
// when no flight completed to warm start from (or the named one did not).
OptimalityGap optimality_gap(const Flight& flight, std::vector<PreparedController>& controllers,
                             const OptimalityOptions& options, Progress* progress = nullptr);

}  // namespace thetad
