#pragma once

#include <CLI/CLI.hpp>

#include "apps/thetad/run_command.hpp"

namespace thetad::app {

struct ApproximationArguments {
  FlightOptions flight;  // the SDRE and θ–D blocks of --settings; --out required
  int every = 10;        // keep every N-th 1 kHz controller sample: 100 Hz
  int threads = 2;
};
CLI::App* add_approximation_command(CLI::App& app, ApproximationArguments& arguments);

// thetad approximation: fly the SDRE with the θ–D computing its own control in the SDRE's place
// at every sample; write <out>/approximation.csv (per kept sample: the relative errors of ΣT_i
// against P, Frobenius and σ_max, and of the control; both inputs) and <out>/approximation.json
// (median, p90, max of each, the flight and its provenance); key=value lines on stdout.
int run_approximation(const ApproximationArguments& arguments);

}  // namespace thetad::app
