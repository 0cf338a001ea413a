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
  std::filesystem::path script;  // scripts/plot_run.py of the source tree unless given
};
CLI::App* add_plot_command(CLI::App& app, PlotArguments& arguments);

// thetad plot: the paper's figures (Figs. 2-17 kinds) and the comparison figures for every run in
// `in` (a `thetad compare` directory, or the <controller>.csv/.json pairs of `thetad run`), the
// controllers overlaid, one file per figure and format in `out`.
//
// thetad checks everything it can before drawing: each CSV header against the columns its result
// file records (the script receives them as JSON and looks its columns up by name) and
// each JSON file's syntax. The script (Debian's /usr/bin/python3, or $THETAD_PYTHON, with
// MPLBACKEND=Agg) draws into a staging directory next to `out`; the files are moved into `out` only
// when every figure is drawn, so a failure leaves `out` as it was.
int run_plot(const PlotArguments& arguments);

}  // namespace thetad::app
