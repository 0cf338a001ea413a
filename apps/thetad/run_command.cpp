#include "apps/thetad/run_command.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "controllers/registry.hpp"
#include "core/settings.hpp"
#include "core/error.hpp"

namespace thetad::app {

namespace {

// Redrawing one line in place only makes sense on a terminal a person watches (not in CI logs).
bool live_progress() { return isatty(fileno(stderr)) == 1 && std::getenv("CI") == nullptr; }

// Passes the scenario's command through and shows how far the run has got: the simulator asks for
// the command once per controller sample in time order, so it doubles as the run's clock.
class ProgressReference final : public ReferenceTrajectory {
 public:
  ProgressReference(const ReferenceTrajectory& command, double duration, const std::string& label)
      : command_(command), duration_(duration), label_(label) {}

  Eigen::Vector3d position(double t) const override {
    const int percent = static_cast<int>(100.0 * t / duration_);
    if (percent != percent_) {
      percent_ = percent;
      std::fprintf(stderr, "\r\033[K%s %d %%", label_.c_str(), percent);
    }
    return command_.position(t);
  }

 private:
  const ReferenceTrajectory& command_;
  double duration_;
  const std::string& label_;
  mutable int percent_ = -1;
};

YAML::Node load_settings_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("cannot read settings file " + file.string() + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return YAML::Load(text.str());
  } catch (const YAML::Exception& error) {
    std::ostringstream message;
    message << file.string() << ":" << error.mark.line + 1 << ":" << error.mark.column + 1
            << ": invalid YAML: " << error.msg;
    throw Error(message.str());
  }
}

// The settings file is a map from controller name to that controller's settings block; a name the
// registry does not know is most likely a typo, so it is an error.
void check_settings_file(const YAML::Node& root, const std::string& source) {
  if (!root.IsDefined() || root.IsNull()) return;
  if (!root.IsMap()) {
    throw SettingsError("settings", "expected a map from controller name to its settings", root.Mark(), source);
  }
  const auto names = ControllerRegistry::instance().names();
  for (const auto& item : root) {
    const std::string name = item.first.Scalar();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::string known;
      for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
      throw SettingsError(name, "unknown controller (known: " + known + ")", item.first.Mark(), source);
    }
  }
}

std::string format(const char* pattern, auto... values) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, pattern, values...);
  return buffer;
}

}  // namespace

std::string status_text(const sim::RunSummary& summary) {
  if (summary.status == sim::RunStatus::completed) return "completed";
  return format("diverged at %.3f s", summary.end_time);
}

void add_flight_options(CLI::App& command, FlightOptions& options) {
  command.add_option("--scenario", options.scenario, "Scenario file (YAML, see docs/scenarios.md)")->required();
  command.add_option("--settings", options.settings,
                     "Controller settings (YAML): a map from controller name to its settings block");
  command.add_option("--seed", options.seed, "Seed of the run's random numbers (default: the scenario's, else 1)")
      ->each([&options](const std::string&) { options.seed_given = true; });
  command.add_flag("--ideal", options.ideal, "No parameter uncertainty, noise or wind");
  command.add_option("--out", options.out, "Output directory")->required();
}

Flight::Flight(const FlightOptions& options)
    : scenario_(load_scenario(options.scenario)),
      settings_(scenario_.simulation_settings()),
      model_(heli::Parameters::nominal(), scenario_.model_options),
      settings_source_(options.settings.string()) {
  if (options.seed_given) settings_.seed = options.seed;
  if (options.ideal) {
    const sim::SimulationSettings ideal = sim::SimulationSettings::ideal();
    settings_.parameter_uncertainty = ideal.parameter_uncertainty;
    settings_.wind_gust.enabled = ideal.wind_gust.enabled;
    settings_.noise = ideal.noise;
  }
  if (!options.settings.empty()) {
    controller_settings_ = load_settings_file(options.settings);
    check_settings_file(controller_settings_, settings_source_);
  }
}

std::string Flight::disturbances() const {
  const auto on = [](bool value) { return value ? "on" : "off"; };
  const sim::NoiseSettings& noise = settings_.noise;
  const bool all = settings_.parameter_uncertainty && settings_.wind_gust.enabled && noise.measurement &&
                   noise.actuator && noise.wind_component && noise.induced_velocity;
  const bool none = !settings_.parameter_uncertainty && !settings_.wind_gust.enabled && !noise.measurement &&
                    !noise.actuator && !noise.wind_component && !noise.induced_velocity;
  if (all) return "all disturbances (the paper's setting)";
  if (none) return "ideal (no uncertainty, noise or wind)";
  return format("uncertainty %s, wind gust %s, measurement noise %s, actuator noise %s, wind noise %s, "
                "induced-velocity noise %s",
                on(settings_.parameter_uncertainty), on(settings_.wind_gust.enabled), on(noise.measurement),
                on(noise.actuator), on(noise.wind_component), on(noise.induced_velocity));
}

std::unique_ptr<Controller> Flight::make_controller(const std::string& name) const {
  const YAML::Node block =
      controller_settings_.IsMap() && controller_settings_[name] ? controller_settings_[name] : YAML::Node();
  const ControllerContext context{model_, scenario_.initial_state, 0.0};
  auto make = [&] { return ControllerRegistry::instance().make(name, block, context); };
  return settings_source_.empty() ? make() : with_settings_source(settings_source_, make);
}

sim::RunResult Flight::fly(Controller& controller, const std::string& label) const {
  const auto start = std::chrono::steady_clock::now();
  sim::RunResult result;
  if (live_progress()) {
    const ProgressReference reference(scenario_.trajectory, settings_.duration, label);
    result = sim::simulate(controller, reference, scenario_.initial_state, settings_, heli::Parameters::nominal(),
                           scenario_.model_options);
    std::fprintf(stderr, "\r\033[K");
  } else {
    std::fprintf(stderr, "%s flying %s (%g s simulated)\n", label.c_str(), scenario_.name.c_str(), settings_.duration);
    result = sim::simulate(controller, scenario_.trajectory, scenario_.initial_state, settings_,
                           heli::Parameters::nominal(), scenario_.model_options);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "%s %s (%.1f s wall)\n", label.c_str(), status_text(result.summary).c_str(), wall);
  return result;
}

CLI::App* add_run_command(CLI::App& app, RunArguments& arguments) {
  auto* run = app.add_subcommand("run", "Fly one controller through a scenario; write <out>/<controller>.csv and .json");
  add_flight_options(*run, arguments.flight);
  run->add_option("--controller", arguments.controller, "Controller name (see thetad list)")->required();
  return run;
}

int run_run(const RunArguments& arguments) {
  const Flight flight(arguments.flight);
  const auto controller = flight.make_controller(arguments.controller);
  const sim::RunResult result = flight.fly(*controller, arguments.controller + ":");

  std::error_code error;
  std::filesystem::create_directories(arguments.flight.out, error);
  if (error) throw Error("cannot create directory " + arguments.flight.out.string() + ": " + error.message());
  const sim::RunFiles files = sim::write_run(result, arguments.flight.out, arguments.controller);

  const sim::RunSummary& s = result.summary;
  const Scenario& scenario = flight.scenario();
  std::printf("%s on %s (%g s, seed %llu, %s): %s%s%s.\n", arguments.controller.c_str(), scenario.name.c_str(),
              scenario.duration, static_cast<unsigned long long>(flight.settings().seed), flight.disturbances().c_str(),
              status_text(s).c_str(), s.reason.empty() ? "" : ": ", s.reason.c_str());
  std::printf("Position error over %lld controller samples: RMS x %.4f, y %.4f, z %.4f m; max x %.4f, y %.4f, "
              "z %.4f m.\n",
              static_cast<long long>(s.controller_samples), s.rms_tracking_error.x(), s.rms_tracking_error.y(),
              s.rms_tracking_error.z(), s.max_tracking_error.x(), s.max_tracking_error.y(), s.max_tracking_error.z());
  std::printf("RMS command: T_mr %.3f N, delta_ped %.4f, delta_col %.4f, delta_lon %.4f, delta_lat %.4f rad; "
              "cost J = %.6g.\n",
              s.command_rms[0], s.command_rms[1], s.command_rms[2], s.command_rms[3], s.command_rms[4], s.cost);
  std::printf("Control compute time per step: median %.1f us, p99 %.1f us.\n", s.compute_ns_median * 1e-3,
              s.compute_ns_p99 * 1e-3);
  for (const auto& [counter, count] : s.controller_counters) std::printf("Controller counter %s: %g.\n", counter.c_str(), count);
  std::printf("Wrote %s and %s.\n", files.csv.c_str(), files.json.c_str());
  return 0;
}

int run_list() {
  const ControllerRegistry& registry = ControllerRegistry::instance();
  std::size_t width = 0;
  for (const auto& name : registry.names()) width = std::max(width, name.size());
  for (const auto& name : registry.names()) {
    std::printf("%-*s  %s\n", static_cast<int>(width), name.c_str(), registry.description(name).c_str());
  }
  return 0;
}

}  // namespace thetad::app
