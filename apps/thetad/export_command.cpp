#include "apps/thetad/export_command.hpp"

#include <cstdio>

#include "core/atomic_file.hpp"
#include "experiment/controller_spec.hpp"

namespace thetad::app {

CLI::App* add_export_command(CLI::App& app, ExportArguments& arguments) {
  auto* command = app.add_subcommand(
      "export", "Write a controller's step at its design as a self-contained, heap-free C++ header (double or "
                "float), with check data recorded along a flight and the check program (docs/onboard.md)");
  arguments.flight.scenario = "scenario-1";
  add_flight_options(*command, arguments.flight, false, false);
  command->get_option("--scenario")->description("Scenario whose initial state is the design point and whose flight "
                                                 "the check data is recorded along (default scenario-1)");
  command->get_option("--out")->description("Folder for LABEL.hpp, LABEL_check_data.hpp and LABEL_check.cpp")->required();
  command->add_option("--controller", arguments.controller, "NAME, LABEL=NAME or LABEL=NAME:SETTINGS.yaml (theta-d, lqr, sdre in mode capped)")
      ->required();
  command->add_option("--check-segments", arguments.check.segments,
                      "Runs of consecutive samples in the check data, spread over the flight")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_option("--check-samples", arguments.check.samples_per_segment, "Consecutive samples per run")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  return command;
}

int run_export(const ExportArguments& arguments) {
  RunControls controls = arguments.flight.controls;
  controls.summary_only = true;
  const Flight flight(arguments.flight.scenario, controls);
  PreparedController prepared =
      flight.prepare(parse_controller_specs({arguments.controller}, arguments.flight.settings).front());
  const ExportedController exported = export_controller(flight, prepared, arguments.check);
  const std::filesystem::path& out = arguments.flight.out;
  write_file_atomically(out / exported.header_file, exported.header);
  write_file_atomically(out / exported.check_data_file, exported.check_data);
  write_file_atomically(out / exported.driver_file, exported.driver);
  std::printf("%s (%s) exported: %s (data checksums: double 0x%016llx, float 0x%016llx)\n", exported.label.c_str(),
              exported.controller.c_str(), (out / exported.header_file).c_str(),
              static_cast<unsigned long long>(exported.checksum_double),
              static_cast<unsigned long long>(exported.checksum_float));
  std::printf("Check: %d samples of %s with the library's u in %s; build and run the check with\n"
              "  c++ -std=c++20 -O2 -fno-exceptions -fno-rtti -o check %s && ./check\n",
              exported.check_samples, flight.scenario().name.c_str(), (out / exported.check_data_file).c_str(),
              (out / exported.driver_file).c_str());
  if (exported.recording_diverged.empty()) return kExitCompleted;
  std::printf("The recording flight diverged (%s): the check's samples are those up to then.\n",
              exported.recording_diverged.c_str());
  return kExitDiverged;
}

}  // namespace thetad::app
