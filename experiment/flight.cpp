#include "experiment/flight.hpp"

#include <chrono>
#include <cstdio>

#include "controllers/registry.hpp"
#include "core/text_file.hpp"
#include "settings/settings.hpp"
#include "experiment/build_info.hpp"
#include "experiment/controller_build.hpp"
#include "experiment/scenario_files.hpp"
#include "experiment/sha256.hpp"

namespace thetad {

namespace {

// The scenario and the SHA-256 of the very bytes it was parsed from.
Scenario load(const std::string& file_or_name, std::string& sha256) {
  const std::filesystem::path file = find_scenario(file_or_name);
  const std::string text = read_text_file(file);
  sha256 = sha256_hex(text);
  return parse_scenario(text, file.string());
}

}  // namespace

Flight::Flight(const std::string& scenario, const RunControls& controls)
    : scenario_(at_speed(controls, load(scenario, provenance_.scenario_sha256))),
      settings_(scenario_.simulation_settings()),
      initial_state_(offset_initial_state(controls, scenario_.initial_state)),
      model_(heli::Parameters::nominal(), scenario_.model_options) {
  apply(controls, settings_);
  provenance_.build = build_info();
  provenance_.scenario_name = scenario_.name;
  // Absolute, so that a replay from another folder finds it.
  provenance_.scenario_file = std::filesystem::absolute(scenario_.source).lexically_normal().string();
  provenance_.model_preset = scenario_.model_preset;
  provenance_.model_options = scenario_.model_options.to_string();
  provenance_.seed = settings_.seed;
  provenance_.dt = settings_.dt;
  const auto entries = [](const Eigen::Vector3d& v) { return std::array<double, 3>{v.x(), v.y(), v.z()}; };
  if (controls.initial_offset) provenance_.initial_offset = entries(*controls.initial_offset);
  if (controls.initial_attitude_offset) provenance_.initial_attitude_offset = entries(*controls.initial_attitude_offset);
  provenance_.speed_scale = controls.speed_scale;
}

std::string Flight::disturbances() const {
  const auto on = [](bool value) { return value ? "on" : "off"; };
  const sim::NoiseSettings& noise = settings_.noise;
  const bool all = settings_.parameter_uncertainty && settings_.wind_gust.enabled && noise.measurement &&
                   noise.actuator && noise.wind_component && noise.induced_velocity;
  const bool none = !settings_.parameter_uncertainty && !settings_.wind_gust.enabled && !noise.measurement &&
                    !noise.actuator && !noise.wind_component && !noise.induced_velocity;
  const char* limits = settings_.actuator_limits.enabled ? "; actuator limits on" : "; no actuator limits";
  if (all) return std::string("all disturbances (the paper's)") + limits;
  if (none && !settings_.actuator_limits.enabled) return "ideal (no uncertainty, noise, wind or actuator limits)";
  if (none) return std::string("no uncertainty, noise or wind") + limits;
  char text[256];
  std::snprintf(text, sizeof text,
                "uncertainty %s, wind gust %s, measurement noise %s, actuator noise %s, wind noise %s, "
                "induced-velocity noise %s",
                on(settings_.parameter_uncertainty), on(settings_.wind_gust.enabled), on(noise.measurement),
                on(noise.actuator), on(noise.wind_component), on(noise.induced_velocity));
  return text + std::string(limits);
}

void Flight::set_keep_log(bool keep) {
  sim::SimulationSettings settings = settings_;
  settings.keep_log = keep;
  settings.validate();
  settings_ = settings;
}

PreparedController Flight::prepare(const ControllerSpec& spec) const {
  ControllerContext context(model_, initial_state_, 0.0);
  context.reference = &scenario_.trajectory;
  context.duration = settings_.duration;
  context.controller_period = settings_.controller_period();
  BuiltController built = build_controller(spec, context);
  return {spec, std::move(built.controller), built.settings, {}};
}

RunResult Flight::fly(PreparedController& prepared, Progress* progress, const std::string& heading) const {
  RunResult result;
  result.spec = prepared.spec;
  result.settings = prepared.settings;
  result.controller_origin =
      prepared.origin.empty() ? ControllerRegistry::instance().origin(prepared.spec.controller) : prepared.origin;
  result.provenance = provenance_;
  if (settings_.measure_compute_time) stamp_host_and_time(result.provenance);
  if (progress) progress->start(heading.empty() ? prepared.spec.label + ":" : heading, settings_.duration);
  const auto start = std::chrono::steady_clock::now();
  const auto report = [progress](double t) { progress->update(t); };
  sim::RunResult flown = sim::simulate(*prepared.controller, scenario_.trajectory, initial_state_, settings_,
                                       heli::Parameters::nominal(), scenario_.model_options,
                                       progress ? std::function<void(double)>(report) : std::function<void(double)>());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.summary = std::move(flown.summary);
  result.log = std::move(flown.log);
  if (settings_.measure_compute_time) result.wall_seconds = wall;
  if (progress) {
    char outcome[160];
    std::snprintf(outcome, sizeof outcome, "%s (%.1f s wall)", status_text(result.summary).c_str(), wall);
    progress->finish(outcome);
  }
  return result;
}

}  // namespace thetad
