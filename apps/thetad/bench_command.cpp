#include "apps/thetad/bench_command.hpp"

#include <cstdio>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/run_files.hpp"

namespace thetad::app {

CLI::App* add_bench_command(CLI::App& app, BenchArguments& arguments) {
  auto* bench = app.add_subcommand(
      "bench", "Per-step cost of controllers on states recorded along a scenario flight, outside the simulation "
               "loop, pinned to one core: median, p10, p90, p99, max, share of the 1 kHz budget");
  arguments.flight.scenario = "scenario-1";
  // It writes no run: no log, summary or timing switches (they would be accepted and ignored).
  add_flight_options(*bench, arguments.flight, false, false);
  add_plant_options(*bench, arguments.flight);
  bench->get_option("--out")->description("JSON file for the figures (optional)");
  bench->add_option("--controllers", arguments.controllers,
                    "Comma-separated NAME, LABEL=NAME or LABEL=NAME:SETTINGS.yaml, or all (every registered controller but the examples); the first flies the recording")
      ->required()
      ->delimiter(',');
  bench->add_option("--samples", arguments.timing.samples,
                    "Timed steps per pass: consecutive 1 kHz samples in --segments runs spread over the flight")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  bench->add_option("--segments", arguments.timing.segments, "Runs of consecutive samples")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  bench->add_option("--repetitions", arguments.timing.repetitions, "Timed passes over the states per controller")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  bench->add_option("--warmup", arguments.timing.warmup_passes, "Untimed passes first")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  bench->add_option("--cpu", arguments.timing.cpu, "Core to pin to (-1: the last this process may use; -2: none)")
      ->capture_default_str();
  return bench;
}

int run_bench(const BenchArguments& arguments) {
  const FlightOptions& options = arguments.flight;
  RunControls controls = options.controls;
  controls.summary_only = true;
  // --plant without --scenario flies the plant, not the default scenario-1.
  FlightOptions chosen = options;
  if (!options.plant.empty() && options.scenario == "scenario-1") chosen.scenario.clear();
  const Flight flight = flight_of(chosen, controls);
  const std::vector<ControllerSpec> specs = parse_controller_specs(arguments.controllers, options.settings);
  std::vector<PreparedController> controllers;
  for (const auto& spec : specs) controllers.push_back(flight.prepare(spec));
  if (!options.out.empty() && options.out.has_parent_path()) prepare_output_folder(options.out.parent_path());

  Progress progress(Progress::mode_for_stderr(options.quiet));
  const RecordedSamples samples = record_samples(flight, controllers.front(), &progress);

  const StepTimingReport report =
      time_steps(controllers, samples, flight.scenario().initial_state, flight.plant().input_dim(), arguments.timing);
  std::printf("%s: states recorded along %g s flown by %s\n", flight.scenario().name.c_str(),
              flight.settings().duration, samples.recorded_with.c_str());
  std::fputs(step_timing_table(report).c_str(), stdout);
  if (!options.out.empty()) {
    write_file_atomically(options.out, bench_json(flight, samples, report).dump(2) + "\n");
    std::printf("Wrote %s.\n", options.out.c_str());
  }
  if (samples.status == sim::RunStatus::completed) return kExitCompleted;
  std::printf("The recording flight %s (%s): the states are those up to then.\n", sim::status_name(samples.status),
              samples.reason.c_str());
  return kExitDiverged;
}

}  // namespace thetad::app
