#pragma once

#include <string>
#include <vector>

#include "experiment/flight.hpp"
#include "experiment/run_result.hpp"
#include "optimal/optimal_control.hpp"

namespace thetad {

struct OptimalityOptions {
  double control_interval = 0.05;  // s: the input is held this long in the transcription (a multiple of T_c)
  // s: the segment compared starts here and runs to the end of the flight (a multiple of T_c). From
  // 0 every flight starts in the scenario's initial state; later each is in its own state.
  double start = 0.0;
  std::string warm_start;          // from 0: the label of the flight to start from; empty: the cheapest completed one
  OptimalControlSettings solver;
};

// The optimum of the segment from one flight's state at its start, warm-started from that flight:
// the problem, its solution, and the optimum as a run (its log, summary and the transcription in
// its settings).
struct SegmentOptimum {
  std::string from;  // the label of the flight it starts from
  OptimalControlProblem problem;
  OptimalControlSolution solution;
  RunResult run;  // labelled "optimal", or "optimal-from-LABEL" for a segment from mid-flight
};

// How far each controller's flight is from the optimum of the same problem over a segment of it.
struct OptimalityGap {
  std::vector<RunResult> flights;
  std::vector<double> costs;  // each flight's J over the segment (its summary's J from t = 0); NaN: did not complete
  // From t = 0: one, from the warm-start flight, for every flight. From mid-flight: one per
  // completed flight, from its state.
  std::vector<SegmentOptimum> optima;

  // The optimum flight i is compared with, or nullptr when it did not complete.
  const SegmentOptimum* optimum_for(std::size_t i) const;
  // 100 (J_i − J*) / J* over the segment, J* as the run metrics sum the optimum's samples (the
  // flights' way): how much more flight i costs than the optimum, in percent.
  double gap_percent(std::size_t i) const;
};

// The optimal control problem of `flight`'s scenario from options.start to the end of the flight,
// priced as simulate() prices J, on the controllers' model, from the scenario's initial state.
// Throws thetad::Error when the flight is not ideal, has actuator limits, does not log every
// sample, or the start or the segment is not a whole number of controller periods or control
// intervals (nothing needs to fly to find out).
OptimalControlProblem optimality_problem(const Flight& flight, const OptimalityOptions& options);

// Flies every controller through `flight`, then solves the optimal control problem of the segment
// (optimality_problem) by multiple shooting (solve_optimal_control): from t = 0 once, from the
// warm-start flight; from mid-flight once per completed flight, from its state and warm-started by
// it. Throws thetad::Error naming what is wrong before anything flies, and when no flight
// completed to warm start from (or the named one did not).
OptimalityGap optimality_gap(const Flight& flight, std::vector<PreparedController>& controllers,
                             const OptimalityOptions& options, Progress* progress = nullptr);

}  // namespace thetad
