#pragma once

#include <string>

#include "experiment/flight.hpp"
#include "experiment/run_result.hpp"
#include "optimal/optimal_control.hpp"

namespace thetad {

// An optimum of `flight`'s problem as a run of that flight: its samples as log rows (the run-log
// columns, the commands applied as they are and measured without noise), its J and its J_dev by
// the flights' own metrics, and the transcription, Ipopt's outcome and `warm_start` in its
// settings. Labelled `label`; a solve that did not converge is a failed run.
RunResult optimum_run(const Flight& flight, const OptimalControlProblem& problem, const OptimalControlSolution& solution,
                      const std::string& warm_start, double control_interval, double tolerance, const std::string& label);

}  // namespace thetad
