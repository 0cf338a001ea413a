#include "apps/thetad/compare_command.hpp"

#include <cstdio>
#include <filesystem>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "experiment/comparison.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/run_files.hpp"

namespace thetad::app {

CLI::App* add_compare_command(CLI::App& app, CompareArguments& arguments) {
  auto* compare = app.add_subcommand(
      "compare", "Fly several controllers through a scenario on the same seed; print a table, write "
                 "<out>/comparison.json. Exit code 0: all completed, 3: any diverged or failed");
  add_flight_options(*compare, arguments.flight, false);
  add_plant_options(*compare, arguments.flight);
  compare->add_option("--controllers", arguments.controllers,
                      "Comma-separated NAME, LABEL=NAME or LABEL=NAME:SETTINGS.yaml "
                      "(e.g. paper=theta-d,tuned=theta-d:out/tune/theta-d-tuned.yaml,sdre), or all (every registered "
                      "controller but the examples)")
      ->delimiter(',');
  compare->add_option("--controllers-file", arguments.controllers_file,
                      "YAML file with a `controllers:` list of {label, controller, settings} (instead of --controllers)");
  compare->get_option("--out")->required();
  return compare;
}

int run_compare(const CompareArguments& arguments) {
  const FlightOptions& options = arguments.flight;
  const Flight flight = flight_of(options, options.controls);
  if (arguments.controllers.empty() == arguments.controllers_file.empty())
    throw Error("thetad compare needs --controllers or --controllers-file (one of them)");
  const std::vector<ControllerSpec> specs = arguments.controllers_file.empty()
                                                ? parse_controller_specs(arguments.controllers, options.settings)
                                                : load_controller_specs(arguments.controllers_file);
  std::vector<PreparedController> controllers;
  for (const auto& spec : specs) controllers.push_back(flight.prepare(spec));
  prepare_output_folder(options.out);
  // A comparison.json left by an earlier compare would describe runs this one replaces.
  const auto comparison_file = options.out / "comparison.json";
  std::error_code error;
  std::filesystem::remove(comparison_file, error);
  if (error) throw Error("cannot remove the old " + comparison_file.string() + ": " + error.message());

  Progress progress(Progress::mode_for_stderr(options.quiet));
  std::vector<RunResult> results;
  std::vector<RunFiles> files;
  bool all_completed = true;
  for (std::size_t i = 0; i < controllers.size(); ++i) {
    const std::string heading = "[" + std::to_string(i + 1) + "/" + std::to_string(controllers.size()) + "] " +
                                controllers[i].spec.label + ":";
    results.push_back(flight.fly(controllers[i], &progress, heading));
    files.push_back(write_run_files(results.back(), options.out));
    all_completed = all_completed && results.back().completed();
    // The log goes out of memory as soon as it is on disk: a compare holds one log at a time.
    results.back().log = {};
  }

  std::printf("%s (%g s, seed %llu, %s)\n", flight.scenario().name.c_str(), flight.settings().duration,
              static_cast<unsigned long long>(flight.settings().seed), flight.disturbances().c_str());
  std::fputs(comparison_table(results).c_str(), stdout);
  write_file_atomically(comparison_file, comparison_json(flight, results, files).dump(2) + "\n");
  std::printf("Wrote %s and the result files of each controller in %s.\n", comparison_file.c_str(),
              options.out.c_str());
  return all_completed ? kExitCompleted : kExitDiverged;
}

}  // namespace thetad::app
