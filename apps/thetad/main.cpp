// The thetad command line. Every thetad::Error becomes one clear line on stderr and exit code 1;
// a flight that diverged is exit code 3 (run_command.hpp).
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "apps/thetad/approximation_command.hpp"
#include "apps/thetad/bench_command.hpp"
#include "apps/thetad/campaign_command.hpp"
#include "apps/thetad/compare_command.hpp"
#include "apps/thetad/demo_command.hpp"
#include "apps/thetad/plot_command.hpp"
#include "apps/thetad/design_lqr_command.hpp"
#include "apps/thetad/disturbances_command.hpp"
#include "apps/thetad/export_command.hpp"
#include "apps/thetad/weights_command.hpp"
#include "apps/thetad/optimal_command.hpp"
#include "apps/thetad/option_suggestion.hpp"
#include "apps/thetad/run_command.hpp"
#include "apps/thetad/tune_command.hpp"
#include "apps/thetad/worst_case_command.hpp"
#include "core/text_file.hpp"
#include "experiment/build_info.hpp"
#include "experiment/plugins.hpp"

int main(int argc, char** argv) {
  // Over a file size limit (ulimit -f) a write would end the process by SIGXFSZ, leaving a partial
  // file behind; ignored, the write fails with EFBIG and the writer reports it and cleans up.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"thetad: theta-D, SDRE and LQR control of the X-Cell miniature helicopter"};
  app.set_version_flag("--version", thetad::version_line());
  app.require_subcommand(1);
  // Plug-ins first: the controllers they register are known to every command (--plugin may stand
  // before or after the command's name).
  std::vector<std::string> plugins;
  app.add_option("--plugin", plugins,
                 "Load a controller plug-in (a shared library built with thetad_add_plugin; repeatable; also "
                 "THETAD_PLUGIN_PATH)");
  app.fallthrough();
  // Bad arguments are one line too, in the same form as every other error; the arguments it quotes
  // may hold any bytes, and the line must be UTF-8 (escaped_utf8), as every error line below.
  app.failure_message([](const CLI::App* failed, const CLI::Error& error) {
    return "thetad: error: " + thetad::escaped_utf8(error.what()) + thetad::app::option_suggestion(*failed) +
           " (see --help)\n";
  });

  std::filesystem::path demo_out = "out";
  auto* demo = app.add_subcommand("demo", "Solve the paper-sized Riccati problem and trim the plant; print diagnostics");
  demo->add_option("--out", demo_out, "Output directory")->capture_default_str();

  thetad::app::RunArguments run_arguments;
  auto* run = thetad::app::add_run_command(app, run_arguments);
  thetad::app::CompareArguments compare_arguments;
  auto* compare = thetad::app::add_compare_command(app, compare_arguments);
  thetad::app::DesignLqrArguments design_lqr_arguments;
  auto* design_lqr = thetad::app::add_design_lqr_command(app, design_lqr_arguments);
  thetad::app::WeightsArguments weights_arguments;
  auto* weights = thetad::app::add_weights_command(app, weights_arguments);
  thetad::app::PlotArguments plot_arguments;
  auto* plot = thetad::app::add_plot_command(app, plot_arguments);
  thetad::app::TuneArguments tune_arguments;
  auto* tune = thetad::app::add_tune_command(app, tune_arguments);
  thetad::app::ApproximationArguments approximation_arguments;
  auto* approximation = thetad::app::add_approximation_command(app, approximation_arguments);
  auto* list = app.add_subcommand("list", "List the registered controllers with their descriptions and origins");
  thetad::app::BenchArguments bench_arguments;
  auto* bench = thetad::app::add_bench_command(app, bench_arguments);
  thetad::app::CampaignArguments campaign_arguments;
  auto* campaign = thetad::app::add_campaign_command(app, campaign_arguments);
  thetad::app::OptimalArguments optimal_arguments;
  auto* optimal = thetad::app::add_optimal_command(app, optimal_arguments);
  thetad::app::ExportArguments export_arguments;
  auto* export_command = thetad::app::add_export_command(app, export_arguments);
  thetad::app::DisturbancesArguments disturbances_arguments;
  auto* disturbances = thetad::app::add_disturbances_command(app, disturbances_arguments);
  thetad::app::WorstCaseArguments worst_case_arguments;
  auto* worst_case = thetad::app::add_worst_case_command(app, worst_case_arguments);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help and --version end here with 0; a bad argument is an error like any other: 1.
    return app.exit(error) == 0 ? 0 : 1;
  }
  try {
    for (const auto& library : thetad::plugins_from_environment()) thetad::load_plugin(library);
    for (const auto& library : plugins) thetad::load_plugin(library);
    if (*demo) return thetad::app::run_demo(demo_out);
    if (*run) return thetad::app::run_run(run_arguments);
    if (*compare) return thetad::app::run_compare(compare_arguments);
    if (*list) return thetad::app::run_list();
    if (*tune) return thetad::app::run_tune(tune_arguments);
    if (*approximation) return thetad::app::run_approximation(approximation_arguments);
    if (*plot) return thetad::app::run_plot(plot_arguments);
    if (*design_lqr) return thetad::app::run_design_lqr(design_lqr_arguments);
    if (*weights) return thetad::app::run_weights(weights_arguments);
    if (*bench) return thetad::app::run_bench(bench_arguments);
    if (*campaign) return thetad::app::run_campaign_command(campaign_arguments);
    if (*optimal) return thetad::app::run_optimal(optimal_arguments);
    if (*export_command) return thetad::app::run_export(export_arguments);
    if (*disturbances) return thetad::app::run_disturbances(disturbances_arguments);
    if (*worst_case) return thetad::app::run_worst_case(worst_case_arguments);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "thetad: error: %s\n", thetad::escaped_utf8(e.what()).c_str());
    return 1;
  }
  return 0;
}
