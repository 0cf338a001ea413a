#pragma once

#include "core/sim/flight_computer.hpp"
#include "settings/disturbance_blocks.hpp"

namespace thetad {

// The flight computer's step times (docs/model.md §15.7) from a `thetad bench` file: each timed
// controller's `file.statistic` (median, p90, p99 or max) by its label, in seconds, and as their
// source the file's name, its SHA-256 and the statistic, which every result of the flight records.
// Reads bench.json format_version 1 and 2. Throws thetad::Error naming the file and the field.
void load_step_times(const StepTimeFile& file, sim::FlightComputerSettings& computer);

}  // namespace thetad
