#include "apps/thetad/run_command.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <thread>
#include <optional>
#include <string>

#include "campaigns/factors.hpp"
#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "core/sim/seed.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/flight.hpp"
#include "experiment/plant_registry.hpp"
#include "experiment/replay.hpp"
#include "experiment/result_json.hpp"
#include "experiment/run_files.hpp"
#include "settings/run_settings.hpp"
#include "experiment/json_file.hpp"

namespace thetad::app {

namespace {

void print_summary(const RunResult& result, const Flight& flight, const RunFiles& files) {
  const sim::RunSummary& s = result.summary;
  std::printf("%s on %s (%g s, seed %llu, %s): %s%s%s.\n", result.spec.label.c_str(), flight.scenario().name.c_str(),
              s.settings.duration, static_cast<unsigned long long>(s.settings.seed), flight.disturbances().c_str(),
              status_text(s).c_str(), s.reason.empty() ? "" : ": ", s.reason.c_str());
  if (!s.tracked.empty()) {
    std::string rms, max;
    for (std::size_t i = 0; i < s.tracked.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      char entry[96];
      std::snprintf(entry, sizeof entry, "%s%s %.4f %s", i ? ", " : "", s.tracked[i].axis.c_str(),
                    s.rms_tracking_error[k], s.tracked[i].command.unit.c_str());
      rms += entry;
      std::snprintf(entry, sizeof entry, "%s%s %.4f %s", i ? ", " : "", s.tracked[i].axis.c_str(),
                    s.max_tracking_error[k], s.tracked[i].command.unit.c_str());
      max += entry;
    }
    std::printf("Tracking error over %lld controller samples: RMS %s; max %s.\n",
                static_cast<long long>(s.controller_samples), rms.c_str(), max.c_str());
  }
  std::string effort;
  for (std::size_t k = 0; k < s.inputs.size(); ++k) {
    char entry[96];
    std::snprintf(entry, sizeof entry, "%s%s %.4g%s%s", k ? ", " : "", s.inputs[k].name.c_str(),
                  s.command_rms[static_cast<Eigen::Index>(k)], s.inputs[k].unit.empty() ? "" : " ",
                  s.inputs[k].unit.c_str());
    effort += entry;
  }
  std::printf("RMS command: %s; cost J = %.6g over %lld controller samples.\n", effort.c_str(), s.cost,
              static_cast<long long>(s.controller_samples));
  if (s.settings.measure_compute_time)
    std::printf("In-flight step time (includes the simulation's noise; thetad bench measures the per-step cost): "
                "median %.1f us, p99 %.1f us.\n",
                s.compute_ns_median * 1e-3, s.compute_ns_p99 * 1e-3);
  if (s.computer)
    std::printf("Flight computer (docs/model.md §15.7): %lld computations, %lld missed deadlines (at most %lld in a "
                "row), %lld samples skipped, %lld aborted; latency mean %.3g ms, max %.3g ms.\n",
                static_cast<long long>(s.computer->computations), static_cast<long long>(s.computer->missed_deadlines),
                static_cast<long long>(s.computer->longest_missed_run), static_cast<long long>(s.computer->skipped_samples),
                static_cast<long long>(s.computer->aborted), s.computer->mean_latency * 1e3, s.computer->max_latency * 1e3);
  for (const auto& [counter, count] : s.controller_counters) std::printf("Controller counter %s: %g.\n", counter.c_str(), count);
  for (const CertificateWorst& worst : s.certificates)
    std::printf("Certificate %s: %s %.4g at t = %.4g s.\n", worst.certificate.column.header().c_str(),
                worst.certificate.worst == ControllerColumn::Worst::largest ? "largest" : "smallest", worst.value,
                worst.t);
  if (files.csv.empty()) {
    std::printf("Wrote %s (summary only).\n", files.json.c_str());
  } else {
    std::printf("Wrote %s and %s.\n", files.csv.c_str(), files.json.c_str());
  }
}

int run_replay(const RunArguments& arguments) {
  Progress progress(Progress::mode_for_stderr(arguments.flight.quiet));
  if (!arguments.flight.out.empty()) {
    const std::string label = read_json_file(arguments.replay).value("label", "");
    std::error_code error;
    if (std::filesystem::equivalent(arguments.flight.out / (label + ".json"), arguments.replay, error))
      throw Error("--out " + arguments.flight.out.string() + " would overwrite " + arguments.replay.string() +
                  ", the result being replayed: write the replay elsewhere");
    prepare_output_folder(arguments.flight.out);
  }
  const Replay replayed = replay(arguments.replay, &progress);
  if (!arguments.flight.out.empty()) {
    const RunFiles files = write_run_files(replayed.result, arguments.flight.out);
    std::printf("Wrote %s.\n", files.json.c_str());
  }
  if (!replayed.differences.empty()) {
    std::printf("Replay of %s DIFFERS from the recorded run (beyond %.0e relative):\n", arguments.replay.c_str(),
                kReplayTolerance);
    for (const auto& difference : replayed.differences) std::printf("  %s\n", difference.c_str());
    return kExitReplayDiffers;
  }
  if (replayed.largest_difference == 0.0)
    std::printf("Replay of %s agrees with the recorded run (%s), bit for bit.\n", arguments.replay.c_str(),
                status_text(replayed.result.summary).c_str());
  else
    std::printf("Replay of %s agrees with the recorded run (%s), to %.1e relative: within %.0e, the rounding that "
                "another CPU or build of libm and LAPACK gives.\n",
                arguments.replay.c_str(), status_text(replayed.result.summary).c_str(), replayed.largest_difference,
                kReplayTolerance);
  return replayed.result.completed() ? kExitCompleted : kExitDiverged;
}

}  // namespace

std::uint64_t parse_seed(const std::string& text, const std::string& option) {
  const std::optional<std::uint64_t> seed = sim::parse_seed(text);
  if (!seed) throw CLI::ValidationError(option, "'" + text + "': " + std::string(sim::kSeedExpected));
  return *seed;
}

namespace {

// `--set NAME=VALUE`: the factor's override of `controls`, its value read as a campaign file's.
void set_factor(const std::string& item, RunControls& controls) {
  const std::size_t equals = item.find('=');
  const std::string name = item.substr(0, equals);
  const Factor* factor = find_factor(name);
  if (equals == std::string::npos || factor == nullptr)
    throw CLI::ValidationError("--set", "'" + item + "': expected NAME=VALUE with NAME one of " + factor_names());
  try {
    factor->set(name, factor_value(*factor, item.substr(equals + 1)), controls);
  } catch (const Error& error) {
    throw CLI::ValidationError("--set", name + ": " + error.what());
  }
}

// The run setting's own option (RunSetting::option), setting it in `controls` as the row says.
void add_setting_option(CLI::App& command, const RunSetting& setting, RunControls& controls) {
  const std::string name(setting.option);
  std::string help(setting.description);
  help[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(help[0])));
  const RunSetting* row = &setting;
  using Option = RunSetting::Option;
  switch (setting.option_form) {
    case Option::on_off:
      command
          .add_option_function<std::string>(
              name, [row, &controls](const std::string& text) { row->apply(text == "on" ? 1.0 : 0.0, controls); },
              help + ": on|off")
          ->check(CLI::IsMember({"on", "off"}));
      return;
    case Option::on_when_given:
    case Option::off_when_given: {
      const bool on = setting.option_form == Option::on_when_given;
      command.add_flag_function(
          name, [row, on, &controls](std::int64_t) { row->apply(on ? 1.0 : 0.0, controls); },
          on ? help : "Off: " + std::string(setting.description));
      return;
    }
    case Option::value:
      break;
    case Option::none:
      return;
  }
  const std::string unit = setting.unit.empty() ? "" : " [" + std::string(setting.unit) + "]";
  if (setting.parse) {
    command.add_option_function<std::string>(
        name,
        [row, name, &controls](const std::string& text) {
          try {
            row->parse(text, controls);
          } catch (const Error& error) {
            throw CLI::ValidationError(name, error.what());
          }
        },
        help);
  } else if (setting.value == RunSetting::Value::whole) {
    command.add_option_function<int>(name, [row, &controls](int value) { row->apply(value, controls); }, help + unit);
  } else {
    command.add_option_function<double>(name, [row, &controls](double value) { row->apply(value, controls); },
                                        help + unit);
  }
}

}  // namespace

void add_flight_options(CLI::App& command, FlightOptions& options, bool scenario_required, bool writes_runs) {
  auto* scenario = command.add_option("--scenario", options.scenario,
                                      "Scenario file (YAML, see docs/scenarios.md) or the name of a shipped one "
                                      "(scenario-1, scenario-2, hover-step, hover-to-hover, fast-forward)");
  if (scenario_required) scenario->required();
  command.add_option("--settings", options.settings,
                     "Controller settings (YAML): a map from controller name to its settings block");
  for (const RunSetting& setting : run_settings()) {
    if (writes_runs || !setting.option_writes_runs) add_setting_option(command, setting, options.controls);
  }
  command.add_option_function<std::vector<std::string>>(
      "--set",
      [&options](const std::vector<std::string>& items) {
        for (const std::string& item : items) set_factor(item, options.controls);
      },
      "A campaign factor for this flight, NAME=VALUE (repeatable; docs/campaigns.md lists them): "
      "uncertainty_scale=2, turbulence_model=dryden, turbulence_intensity=severe, servo_delay_samples=2, slowdown=30, ...");
  command.add_flag("--quiet", options.quiet, "No progress display");
  command.add_option("--out", options.out, "Output directory (created; checked before anything flies)");
}

CLI::Option* add_controllers_option(CLI::App& command, std::vector<std::string>& controllers) {
  return command
      .add_option("--controllers", controllers,
                  "Comma-separated NAME, LABEL=NAME or LABEL=NAME:SETTINGS.yaml, or all (every registered controller "
                  "but the examples)")
      ->delimiter(',')
      ->required();
}

CLI::Option* add_jobs_option(CLI::App& command, int& jobs, const std::string& what) {
  return command.add_option("--jobs", jobs, what + " (default: every core)")->check(CLI::Range(0, 1024));
}

int jobs_or_every_core(int jobs) {
  return jobs > 0 ? jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void add_plant_options(CLI::App& command, FlightOptions& options) {
  command.add_option("--plant", options.plant,
                     "Fly a registered plant (thetad list; a plug-in's too) instead of a scenario, regulated to the "
                     "origin; needs --duration. A scenario file may name a plant instead (docs/plants.md)");
  command.add_option("--initial-state", options.initial_state, "With --plant: the initial state (comma-separated)")
      ->delimiter(',');
}

Flight flight_of(const FlightOptions& options, const RunControls& controls) {
  if (!options.scenario.empty() && !options.plant.empty()) throw Error("--plant and --scenario exclude each other");
  if (options.scenario.empty() && options.plant.empty()) throw Error("give --scenario or --plant");
  std::optional<Eigen::VectorXd> initial_state;
  if (!options.initial_state.empty())
    initial_state = Eigen::Map<const Eigen::VectorXd>(options.initial_state.data(),
                                                      static_cast<Eigen::Index>(options.initial_state.size()));
  return Flight::of_scenario_or_plant(options.scenario, options.plant, initial_state, controls);
}

CLI::App* add_run_command(CLI::App& app, RunArguments& arguments) {
  auto* run = app.add_subcommand(
      "run", "Fly one controller through a scenario; write <out>/<label>.csv and .json. Exit code 0: completed, "
             "3: diverged or the controller failed");
  add_flight_options(*run, arguments.flight, false);
  run->add_option("--controller", arguments.controller,
                  "NAME, LABEL=NAME, NAME:SETTINGS.yaml or LABEL=NAME:SETTINGS.yaml (see thetad list)");
  add_plant_options(*run, arguments.flight);
  run->add_option("--replay", arguments.replay,
                  "Fly again the run a result JSON describes, from what it records, and check that the summary "
                  "agrees (exit code 4 when it does not)");
  return run;
}

int run_run(const RunArguments& arguments) {
  if (!arguments.replay.empty()) return run_replay(arguments);
  if ((arguments.flight.scenario.empty() && arguments.flight.plant.empty()) || arguments.controller.empty() ||
      arguments.flight.out.empty())
    throw Error("thetad run needs --scenario, --controller and --out (or --replay RESULT.json)");
  // Everything that can be wrong is found before the flight: files, specs, the output folder.
  const Flight flight = flight_of(arguments.flight, arguments.flight.controls);
  PreparedController prepared = flight.prepare(parse_controller_specs({arguments.controller}, arguments.flight.settings).front());
  prepare_output_folder(arguments.flight.out);

  Progress progress(Progress::mode_for_stderr(arguments.flight.quiet));
  const RunResult result = flight.fly(prepared, &progress);
  const RunFiles files = write_run_files(result, arguments.flight.out);
  print_summary(result, flight, files);
  return result.completed() ? kExitCompleted : kExitDiverged;
}

int run_list() {
  const ControllerRegistry& registry = ControllerRegistry::instance();
  std::size_t width = 0;
  for (const auto& name : registry.names()) width = std::max(width, name.size());
  for (const auto& name : registry.names()) {
    std::printf("%-*s  %s [%s]\n", static_cast<int>(width), name.c_str(), registry.description(name).c_str(),
                registry.origin(name).c_str());
  }
  const PlantRegistry& plants = PlantRegistry::instance();
  for (const auto& name : plants.names()) std::printf("plant %s  %s\n", name.c_str(), plants.description(name).c_str());
  return 0;
}

}  // namespace thetad::app
