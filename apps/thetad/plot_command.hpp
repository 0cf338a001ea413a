#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace thetad::app {

struct PlotArguments {
  std::filesystem::path in;
  std::filesystem::path out;
  std::vector<std::string> formats{"png", "svg"};
  int dpi = 300;
  std::string baseline;          // the run the difference panels compare with; the first if empty
  std::filesystem::path script;  // the shipped plot_run.py unless given
};
CLI::App* add_plot_command(CLI::App& app, PlotArguments& arguments);

// thetad plot: the figures of every run in `in`, drawn into `out` (experiment/run_figures.hpp).
int run_plot(const PlotArguments& arguments);

}  // namespace thetad::app
