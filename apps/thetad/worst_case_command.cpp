#include "apps/thetad/worst_case_command.hpp"

#include <cstdio>

#include "core/atomic_file.hpp"
#include "core/helicopter/uncertainty.hpp"
#include "experiment/run_files.hpp"
#include "experiment/run_result.hpp"

namespace thetad::app {

CLI::App* add_worst_case_command(CLI::App& app, WorstCaseArguments& arguments) {
  auto* command = app.add_subcommand(
      "worst-case", "Search Table 1's 21 parameter bounds for each controller's worst case on a scenario (a sampled "
                    "design of the box, then NLopt), every other disturbance as the seed draws it; write "
                    "<out>/worst_case.json and <out>/LABEL-worst-case.yaml, which thetad run flies again "
                    "(docs/robustness.md)");
  add_flight_options(*command, arguments.flight, true, false);
  add_controllers_option(*command, arguments.controllers);
  command->add_option("--metric", arguments.metric, "What the worst case maximizes: rms_error_m or cost_dev")
      ->capture_default_str()
      ->check(CLI::IsMember({"rms_error_m", "cost_dev"}));
  command->add_option("--max-evaluations", arguments.options.max_evaluations,
                      "Flights per controller, the sampled design's included")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  command->add_option("--corners", arguments.options.corners, "Random corners of the box in the sampled design")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  command->add_option("--design-seed", arguments.options.design_seed, "Seed of the corners' signs and of NLopt")
      ->capture_default_str();
  arguments.options.threads = 0;  // every core
  add_jobs_option(*command, arguments.options.threads, "Flights of the design at once");
  command->get_option("--out")->required();
  return command;
}

int run_worst_case(const WorstCaseArguments& arguments) {
  const FlightOptions& options = arguments.flight;
  const std::vector<ControllerSpec> specs = parse_controller_specs(arguments.controllers, options.settings);
  prepare_output_folder(options.out);
  tuning::WorstCaseOptions search = arguments.options;
  search.metric = tuning::parse_worst_case_metric(arguments.metric);
  search.threads = jobs_or_every_core(search.threads);
  search.progress = [quiet = options.quiet](const std::string& label, int evaluations, int budget) {
    if (!quiet) std::fprintf(stderr, "%s: %d / %d flights\n", label.c_str(), evaluations, budget);
  };
  const tuning::WorstCases cases = tuning::find_worst_cases(options.scenario, options.controls, specs, search);

  const char* metric = tuning::metric_key(search.metric);
  std::printf("%-16s %-24s %14s %-24s %14s %6s  %s\n", "label", "nominal", metric, "worst", metric, "flights", "stop");
  nlohmann::ordered_json json = tuning::worst_case_json(cases);
  for (std::size_t i = 0; i < cases.controllers.size(); ++i) {
    const tuning::WorstCase& c = cases.controllers[i];
    std::printf("%-16s %-24s %14.6g %-24s %14.6g %6d  %s\n", c.controller.label.c_str(),
                status_text(c.nominal.summary).c_str(), c.nominal.value, status_text(c.worst.summary).c_str(),
                c.worst.value, c.evaluations, c.stop.c_str());
    const auto replay = options.out / (c.controller.label + "-worst-case.yaml");
    const std::string settings =
        c.controller.settings_source.empty() ? "" : " --settings " + c.controller.settings_source;
    write_file_atomically(replay, "# The worst case thetad worst-case found for " + c.controller.label + " (" +
                                      (options.out / "worst_case.json").string() + "): thetad run --scenario " +
                                      replay.string() + " --controller " + c.controller.controller + settings +
                                      " flies it again.\n" +
                                      tuning::worst_case_scenario(cases.provenance.scenario_text, c.worst));
    json["controllers"][i]["replay"] = replay.filename().string();
  }
  const auto names = heli::parameter_uncertainty_names();
  for (const tuning::WorstCase& c : cases.controllers) {
    std::printf("%s worst deviations:", c.controller.label.c_str());
    for (std::size_t k = 0; k < names.size(); ++k)
      if (c.worst.xi[k] != 0.0) std::printf(" %s=%.3g", std::string(names[k]).c_str(), c.worst.xi[k]);
    std::printf("\n");
  }
  write_file_atomically(options.out / "worst_case.json", json.dump(2) + "\n");
  std::printf("Wrote %s\n", (options.out / "worst_case.json").string().c_str());
  return 0;
}

}  // namespace thetad::app
