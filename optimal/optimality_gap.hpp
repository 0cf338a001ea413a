#pragma once

#include <optional>
#include <string>
#include <vector>

#include "experiment/flight.hpp"
#include "experiment/run_result.hpp"
#include "optimal/optimal_control.hpp"

namespace thetad {

// The cost the optimum minimizes and the flights are compared on.
enum class OptimalCost {
  deviation,  // J_dev (docs/model.md §7.2): the comparison's score, one Q, R for every controller
  paper,      // J (Eq. 32) with the plant's design weights: the paper's
};

// "J_dev" or "J", as the results name them.
const char* cost_name(OptimalCost cost);

struct OptimalityOptions {
  OptimalCost cost = OptimalCost::deviation;
  double control_interval = 0.05;  // s: the input is held this long in the transcription (a multiple of T_c)
  // s: the segment compared starts here and runs to the end of the flight (a multiple of T_c). From
  // 0 every flight starts in the scenario's initial state; later each is in its own state.
  double start = 0.0;
  std::string warm_start;          // from 0: the label of the flight to start from; empty: the cheapest completed one
  OptimalControlSettings solver;
};

// An optimum as a run of the flight (its log, summary with J and J_dev, and the transcription in
// its settings) with the solution it comes from.
struct SolvedOptimum {
  OptimalControlSolution solution;
  RunResult run;
};

// The optimum of the segment from one flight's state at its start, warm-started from that flight.
// When the flights have actuator limits, the problem bounds the inputs by their magnitude limits
// (not by their rates) and a second solve, warm-started from the bounded optimum, drops the bounds:
// its cost is at most the bounded one's, within Ipopt's tolerance.
struct SegmentOptimum {
  std::string from;  // the label of the flight it starts from
  OptimalControlProblem problem;
  SolvedOptimum optimum;  // labelled "optimal", or "optimal-from-LABEL" for a segment from mid-flight
  std::optional<SolvedOptimum> unbounded;  // "optimal-unbounded[-from-LABEL]"

  // The optimum's cost, the minimized one (J or J_dev), as its run's summary has it.
  double cost(OptimalCost kind) const;
  double unbounded_cost(OptimalCost kind) const;
};

// How far each controller's flight is from the optimum of the same problem over a segment of it.
struct OptimalityGap {
  OptimalCost cost = OptimalCost::deviation;
  std::vector<RunResult> flights;
  // Each flight's cost over the segment (its summary's from t = 0); NaN: did not complete.
  std::vector<double> costs;
  // From t = 0: one, from the warm-start flight, for every flight. From mid-flight: one per
  // completed flight, from its state.
  std::vector<SegmentOptimum> optima;

  // The optimum flight i is compared with, or nullptr when it did not complete.
  const SegmentOptimum* optimum_for(std::size_t i) const;
  // 100 (J_i − J*) / J* over the segment, J* as the run metrics sum the optimum's samples (the
  // flights' way): how much more flight i costs than the optimum, in percent. The bounded optimum's
  // when the flights have limits.
  double gap_percent(std::size_t i) const;
  // The same against the unbounded optimum; NaN without limits.
  double unbounded_gap_percent(std::size_t i) const;
};

// The optimal control problem of `flight`'s scenario from options.start to the end of the flight,
// priced as simulate() prices J or J_dev, on the controllers' model, from the scenario's initial
// state, bounded by the actuators' magnitude limits when the flight has them. Throws thetad::Error
// when the flight has a disturbance, does not log every sample, has no J_dev to give (a plant
// without trims, a reference beyond them) when that is the cost, or the start or the segment is
// not a whole number of controller periods or control intervals (nothing needs to fly to find out).
OptimalControlProblem optimality_problem(const Flight& flight, const OptimalityOptions& options);

// Flies every controller through `flight`, then solves the optimal control problem of the segment
// (optimality_problem) by multiple shooting (solve_optimal_control): from t = 0 once, from the
// warm-start flight; from mid-flight once per completed flight, from its state and warm-started by
// it. Throws thetad::Error naming what is wrong before anything flies, and when no flight
// completed to warm start from (or the named one did not).
OptimalityGap optimality_gap(const Flight& flight, std::vector<PreparedController>& controllers,
                             const OptimalityOptions& options, Progress* progress = nullptr);

}  // namespace thetad
