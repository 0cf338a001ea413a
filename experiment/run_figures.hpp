#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace thetad {

// The paper's figures (Figs. 2-17 kinds) and the comparison figures of the runs in a folder, drawn
// by the shipped plot_run.py (`thetad plot`, thetad.plot).
struct FigureOptions {
  std::vector<std::string> formats{"png", "svg"};
  int dpi = 300;
  std::string baseline;          // the run the difference panels compare with; the first if empty
  std::filesystem::path script;  // the shipped scripts/plot_run.py if empty
};

// Draws every run in `in` (a `thetad compare` folder, or the LABEL.csv/.json pairs of `thetad run`),
// the controllers overlaid, one file per figure and format, into `out`; returns the files, sorted.
//
// Everything that can be checked is checked before drawing: each CSV header against the columns its
// result file records (the script receives them as JSON and looks its columns up by name), each
// JSON file's syntax, a log in every run, the baseline among the runs. The script (Debian's
// /usr/bin/python3, or $THETAD_PYTHON, with MPLBACKEND=Agg) draws into a staging folder next to
// `out`; the files move into `out` only when every figure is drawn, so a failure leaves `out` as it
// was. What the script prints goes to stderr.
std::vector<std::filesystem::path> draw_run_figures(const std::filesystem::path& in, const std::filesystem::path& out,
                                                    const FigureOptions& options);

}  // namespace thetad
