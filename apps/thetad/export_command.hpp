#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "apps/thetad/run_command.hpp"
#include "export/controller_export.hpp"

namespace thetad::app {

struct ExportArguments {
  FlightOptions flight;    // --scenario (default scenario-1: the design state and the check's flight), --settings, ...
  std::string controller;  // a SPEC, as for run
  ExportCheckOptions check;
};
CLI::App* add_export_command(CLI::App& app, ExportArguments& arguments);

// thetad export: the controller's step at its design as a self-contained C++ header, with the
// check data recorded along the scenario's flight and the check program (docs/onboard.md), in
// --out; a summary on stdout.
int run_export(const ExportArguments& arguments);

}  // namespace thetad::app
