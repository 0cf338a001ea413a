#include "apps/thetad/disturbances_command.hpp"

#include <cstdio>

#include "core/atomic_file.hpp"
#include "experiment/disturbance_effects.hpp"
#include "experiment/run_files.hpp"

namespace thetad::app {

CLI::App* add_disturbances_command(CLI::App& app, DisturbancesArguments& arguments) {
  auto* command = app.add_subcommand(
      "disturbances", "Which disturbance does what: fly the scenario with each of its disturbances alone, all, none "
                      "and all but one, every controller on the same seed; print the RMS error and the costs of "
                      "each flight, write <out>/disturbances.json (docs/robustness.md)");
  add_flight_options(*command, arguments.flight, true, false);
  add_controllers_option(*command, arguments.controllers);
  add_jobs_option(*command, arguments.jobs);
  command->get_option("--out")->required();
  return command;
}

int run_disturbances(const DisturbancesArguments& arguments) {
  const FlightOptions& options = arguments.flight;
  const std::vector<ControllerSpec> specs = parse_controller_specs(arguments.controllers, options.settings);
  prepare_output_folder(options.out);
  Progress progress(Progress::mode_for_stderr(options.quiet));
  const DisturbanceEffects effects =
      fly_disturbance_effects(options.scenario, options.controls, specs, jobs_or_every_core(arguments.jobs), &progress);
  std::fputs(disturbance_table(effects).c_str(), stdout);
  const auto file = options.out / "disturbances.json";
  write_file_atomically(file, disturbance_json(effects).dump(2) + "\n");
  std::printf("Wrote %s\n", file.string().c_str());
  return 0;
}

}  // namespace thetad::app
