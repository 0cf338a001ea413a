#include "apps/thetad/approximation_command.hpp"

#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "controllers/feedforward_controller.hpp"
#include "controllers/sdre.hpp"
#include "controllers/theta_d.hpp"
#include "core/atomic_file.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/result_json.hpp"
#include "experiment/run_files.hpp"
#include "tuning/approximation_error.hpp"
#include "tuning/record.hpp"

namespace thetad::app {

CLI::App* add_approximation_command(CLI::App& app, ApproximationArguments& a) {
  auto* command = app.add_subcommand(
      "approximation", "How well theta-D approximates the SDRE along an SDRE flight: relative errors of sum T_i "
                       "against P (Frobenius, sigma_max) and of the control, at every kept sample");
  add_flight_options(*command, a.flight);
  command->get_option("--out")->required();
  command->add_option("--every", a.every, "Keep every N-th controller sample")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command->add_option("--threads", a.threads, "Threads of the cold solves after the flight")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  return command;
}

int run_approximation(const ApproximationArguments& a) {
  // Inputs first: scenario, controls, settings, the output folder; then the flight.
  RunControls controls = a.flight.controls;
  controls.summary_only = true;
  const Flight flight(a.flight.scenario, controls);
  const YAML::Node settings = a.flight.settings.empty() ? YAML::Node() : load_settings_file(a.flight.settings);
  const PreparedController sdre = flight.prepare(parse_controller_spec("sdre", settings, a.flight.settings.string()));
  PreparedController theta_d = flight.prepare(parse_controller_spec("theta-d", settings, a.flight.settings.string()));
  prepare_output_folder(a.flight.out);

  Progress progress(Progress::mode_for_stderr(a.flight.quiet));
  const auto start = std::chrono::steady_clock::now();
  const auto& sdre_controller = paper_form<SdreController>(*sdre.controller, "thetad approximation");
  const tuning::TuningRecord record =
      tuning::record_sdre_flight(flight, sdre_controller, a.every, a.threads, &progress, theta_d.controller.get());
  auto& series = paper_form<ThetaDController>(*theta_d.controller, "thetad approximation");
  series.reset(flight.initial_state(), 0.0);
  const tuning::ApproximationError error = tuning::approximation_error(sdre_controller, series, record, a.threads);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::ordered_json json;
  json["scenario"] = flight.scenario().name;
  json["duration_s"] = flight.settings().duration;
  json["seed"] = flight.settings().seed;
  json["disturbances"] = flight.disturbances();
  json["every"] = a.every;
  json["sdre_settings"] = yaml_to_json(sdre.settings);
  json["theta_d_settings"] = yaml_to_json(theta_d.settings);
  json["errors"] = tuning::approximation_summary(error);
  json["seconds"] = seconds;
  json["provenance"] = to_json(flight.provenance());
  const auto csv = a.flight.out / "approximation.csv", report = a.flight.out / "approximation.json";
  write_file_atomically(csv, tuning::approximation_csv(error));
  write_file_atomically(report, json.dump(2) + "\n");

  std::printf("scenario=%s duration_s=%g seed=%llu samples=%zu\n", flight.scenario().name.c_str(),
              flight.settings().duration, static_cast<unsigned long long>(flight.settings().seed), error.time.size());
  for (const char* name : {"frobenius", "sigma", "control"}) {
    const auto& q = json["errors"][name];
    std::printf("%s_relative median=%.4g p90=%.4g max=%.4g\n", name, q["median"].get<double>(), q["p90"].get<double>(),
                q["max"].get<double>());
  }
  std::printf("wrote=%s,%s\n", csv.c_str(), report.c_str());
  return kExitCompleted;
}

}  // namespace thetad::app
