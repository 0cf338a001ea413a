#include "apps/thetad/design_lqr_command.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <unistd.h>

#include <yaml-cpp/yaml.h>

#include "controllers/lqr_scheduled.hpp"
#include "core/error.hpp"
#include "settings/settings.hpp"
#include "settings/yaml_document.hpp"
#include "scenarios/scenario.hpp"

namespace thetad::app {

CLI::App* add_design_lqr_command(CLI::App& app, DesignLqrArguments& arguments) {
  auto* command = app.add_subcommand(
      "design-lqr", "Design the lqr-scheduled table (trims, linearizations, LQR gains over a flight-condition grid)");
  command->add_option("--grid", arguments.grid,
                      "Grid file (YAML or JSON: speeds, courses_deg, climb_rates, altitude); default: the envelope")
      ->check(CLI::ExistingFile);
  command->add_option("--scenario", arguments.scenario, "Take the model options from this scenario")
      ->check(CLI::ExistingFile);
  command->add_option("--out", arguments.out, "Table file to write (JSON)")->required();
  return command;
}

int run_design_lqr(const DesignLqrArguments& arguments) {
  LqrScheduleGrid grid = LqrScheduleGrid::envelope();
  if (!arguments.grid.empty()) {
    const YAML::Node root = load_yaml_file(arguments.grid);
    grid = with_settings_source(arguments.grid.string(), [&] { return read_lqr_grid(Settings(root)); });
  }
  const heli::ModelOptions options =
      arguments.scenario.empty() ? heli::ModelOptions::resolved() : load_scenario(arguments.scenario).model_options;
  const heli::Helicopter model(heli::Parameters::nominal(), options);

  // Redrawing one line in place only on a terminal a person watches (plain lines in CI logs).
  const bool live = isatty(fileno(stderr)) == 1 && std::getenv("CI") == nullptr;
  const auto start = std::chrono::steady_clock::now();
  std::size_t governor_points = 0;
  const DesignDefaults defaults = model.design_defaults();
  const LqrScheduleTable table = design_lqr_schedule(
      model, grid, defaults.state_weights, defaults.input_weights,
      [&](std::size_t done, std::size_t total, const LqrSchedulePoint& point) {
        const bool governor = point.rotor_speed_model == heli::ModelOptions::RotorSpeedModel::governor;
        governor_points += governor ? 1 : 0;
        std::fprintf(stderr, "%s[%zu/%zu] speed %5.2f m/s  course %5.1f deg  climb %5.2f m/s  %s  Omega %.1f rad/s%s",
                     live ? "\r\033[K" : "", done, total, point.speed, point.course * 180.0 / std::numbers::pi,
                     point.climb_rate, governor ? "governor" : "thrust_inversion", point.rotor_speed,
                     live ? "" : "\n");
      });
  if (live) std::fprintf(stderr, "\r\033[K");
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  save_lqr_schedule(table, arguments.out);
  std::printf("%zu grid points (%zu speeds x %zu courses x %zu climb rates), %zu with the governor rotor model, "
              "designed in %.1f s; wrote %s\n",
              table.points.size(), grid.speeds.size(), grid.courses.size(), grid.climb_rates.size(), governor_points,
              wall, arguments.out.string().c_str());
  return 0;
}

}  // namespace thetad::app
