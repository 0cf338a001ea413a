#include "apps/thetad/plot_command.hpp"

#include <cstdio>

#include "core/error.hpp"
#include "experiment/python_script.hpp"
#include "experiment/run_figures.hpp"

namespace thetad::app {

CLI::App* add_plot_command(CLI::App& app, PlotArguments& arguments) {
  auto* plot = app.add_subcommand(
      "plot", "Draw the paper's figures (Figs. 2-17) and comparison figures for the runs in a directory");
  plot->add_option("--in", arguments.in, "Directory written by thetad compare (or thetad run)")->required();
  plot->add_option("--out", arguments.out, "Directory for the figures (created; existing files are replaced)")
      ->required();
  plot->add_option("--format,--formats", arguments.formats, "Comma-separated file formats (png, svg, pdf)")
      ->delimiter(',')
      ->check(CLI::IsMember({"png", "svg", "pdf"}))
      ->capture_default_str();
  plot->add_option("--dpi", arguments.dpi, "Resolution of raster formats (the figures are 8.5 or 17.6 cm wide)")
      ->check(CLI::Range(30, 600))
      ->capture_default_str();
  plot->add_option("--baseline", arguments.baseline,
                   "Label of the run the difference panels (Euler angles) compare with; default: the first run");
  arguments.script = shipped_script("plot_run.py");
  plot->add_option("--script", arguments.script, "The plotting script")->capture_default_str();
  return plot;
}

int run_plot(const PlotArguments& arguments) {
  if (!std::filesystem::is_directory(arguments.in)) throw Error("--in " + arguments.in.string() + ": no such directory");
  FigureOptions options;
  options.formats = arguments.formats;
  options.dpi = arguments.dpi;
  options.baseline = arguments.baseline;
  options.script = arguments.script;
  const std::vector<std::filesystem::path> figures = draw_run_figures(arguments.in, arguments.out, options);
  std::printf("Wrote %zu files to %s:\n", figures.size(), arguments.out.c_str());
  for (const auto& figure : figures) std::printf("  %s\n", (arguments.out / figure.filename()).c_str());
  return 0;
}

}  // namespace thetad::app
