#pragma once

#include <filesystem>
#include <vector>

#include <CLI/CLI.hpp>

#include "controllers/weights_design.hpp"

namespace thetad::app {

struct WeightsArguments {
  WeightDesignInputs inputs;
  std::filesystem::path grid;      // the envelope (YAML/JSON, as design-lqr reads it); empty: the default
  std::vector<double> speeds, courses_deg, climb_rates;  // or the envelope's lists on the command line
  std::filesystem::path scenario;  // its model options; empty: the resolved preset
  std::filesystem::path out;
};
CLI::App* add_weights_command(CLI::App& app, WeightsArguments& arguments);

// thetad weights: designs Q and R (design_weights) and writes the settings file every built-in
// controller flies, with its design inputs and checks; the checks on stdout. Exit 1 when the
// checks cannot be met (the file is written all the same, saying so).
int run_weights(const WeightsArguments& arguments);

}  // namespace thetad::app
