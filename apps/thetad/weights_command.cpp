#include "apps/thetad/weights_command.hpp"

#include <chrono>
#include <cstdio>

#include <yaml-cpp/yaml.h>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "scenarios/scenario.hpp"
#include "settings/settings.hpp"
#include "settings/yaml_document.hpp"

namespace thetad::app {

CLI::App* add_weights_command(CLI::App& app, WeightsArguments& arguments) {
  auto* command = app.add_subcommand(
      "weights", "Design Q and R for every built-in controller: Bryson's rule, then checks of each controller's "
                 "sampled loop over an envelope of trims (docs/weights.md)");
  WeightDesignInputs& in = arguments.inputs;
  command->add_option("--position", in.position, "Allowed position error (m)")->capture_default_str();
  command->add_option("--velocity", in.velocity, "Allowed body velocity error (m/s)")->capture_default_str();
  command->add_option("--attitude", in.attitude, "Allowed roll and pitch error (rad)")->capture_default_str();
  command->add_option("--heading", in.heading, "Allowed heading error (rad)")->capture_default_str();
  command->add_option("--rate", in.rate, "Allowed body rate error (rad/s)")->capture_default_str();
  command->add_option("--flapping", in.flapping, "Allowed flapping error (rad)")->capture_default_str();
  command->add_option("--integral", in.integral, "Allowed position-error integral (m s)")->capture_default_str();
  command->add_option("--headroom-share", in.headroom_share, "Share of the input headroom the responses may use")
      ->capture_default_str();
  command->add_option("--grid", arguments.grid,
                      "Envelope of the checks (YAML or JSON: speeds, courses_deg, climb_rates); default: the scheduled "
                      "LQR's")
      ->check(CLI::ExistingFile);
  command->add_option("--speeds", arguments.speeds, "Envelope speeds (m/s), instead of a grid file");
  command->add_option("--courses-deg", arguments.courses_deg, "Envelope courses (deg), instead of a grid file");
  command->add_option("--climb-rates", arguments.climb_rates, "Envelope climb rates (m/s), instead of a grid file");
  command->add_option("--scenario", arguments.scenario, "Take the model options from this scenario")
      ->check(CLI::ExistingFile);
  command->add_option("--out", arguments.out, "Settings file to write (YAML)")->required();
  return command;
}

int run_weights(const WeightsArguments& arguments) {
  WeightDesignInputs inputs = arguments.inputs;
  if (!arguments.grid.empty()) {
    const YAML::Node root = load_yaml_file(arguments.grid);
    inputs.envelope = with_settings_source(arguments.grid.string(), [&] { return read_lqr_grid(Settings(root)); });
  }
  if (!arguments.speeds.empty() || !arguments.courses_deg.empty() || !arguments.climb_rates.empty()) {
    if (!arguments.grid.empty()) throw Error("weights: give the envelope as --grid or as its lists, not both");
    YAML::Node lists;
    if (!arguments.speeds.empty()) lists["speeds"] = arguments.speeds;
    if (!arguments.courses_deg.empty()) lists["courses_deg"] = arguments.courses_deg;
    if (!arguments.climb_rates.empty()) lists["climb_rates"] = arguments.climb_rates;
    inputs.envelope = with_settings_source("the command line", [&] { return read_lqr_grid(Settings(lists)); });
  }
  const heli::ModelOptions options =
      arguments.scenario.empty() ? heli::ModelOptions::resolved() : load_scenario(arguments.scenario).model_options;
  const heli::Helicopter model(heli::Parameters::nominal(), options);
  const auto start = std::chrono::steady_clock::now();
  const WeightDesign design = design_weights(model, inputs);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string text = weights_settings_text(design);
  write_file_atomically(arguments.out, text);
  // The checks, as the file's comments say them.
  for (std::size_t begin = 0; begin < text.size();) {
    const std::size_t end = text.find('\n', begin);
    if (text.compare(begin, 2, "# ") == 0) std::printf("%s\n", text.substr(begin + 2, end - begin - 2).c_str());
    begin = end + 1;
  }
  std::printf("designed in %.1f s; wrote %s\n", wall, arguments.out.string().c_str());
  return design.holds ? 0 : 1;
}

}  // namespace thetad::app
