#include "experiment/run_controls.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "core/helicopter/uncertainty.hpp"

namespace thetad {

namespace {

std::string seconds(double value) {
  std::ostringstream text;
  text.precision(12);
  text << value << " s";
  return text.str();
}

}  // namespace

void apply(const RunControls& controls, sim::SimulationSettings& settings) {
  if (controls.duration) {
    const double duration = *controls.duration;
    if (!(duration > 0.0) || !(duration <= sim::SimulationSettings::kMaxDuration))
      throw Error("duration " + seconds(duration) + ": must be > 0 and at most 86400 s (one simulated day)");
    settings.duration = duration;
  }
  if (controls.dt) {
    const double dt = *controls.dt, period = settings.controller_period();
    if (!(dt > 0.0) || !std::isfinite(dt)) throw Error("dt " + seconds(dt) + ": must be > 0");
    const double steps = std::round(period / dt);
    if (steps < 1.0 || std::abs(steps * dt - period) > 1e-9 * period)
      throw Error("dt " + seconds(dt) + " does not divide the controller period " + seconds(period) +
                  ": the controller samples every " + seconds(period) +
                  " with zero-order hold, so the plant step must be that period divided by a whole number");
    settings.dt = period / steps;
    settings.controller_period_steps = static_cast<int>(steps);
  }
  if (controls.log_every) {
    if (*controls.log_every < 1) throw Error("log_every " + std::to_string(*controls.log_every) + ": must be >= 1");
    settings.log_every = *controls.log_every;
  }
  if (controls.seed) settings.seed = *controls.seed;
  if (controls.ideal) {
    const sim::SimulationSettings ideal = sim::SimulationSettings::ideal();
    settings.parameter_uncertainty = ideal.parameter_uncertainty;
    settings.wind_gust.enabled = ideal.wind_gust.enabled;
    settings.noise = ideal.noise;
    settings.actuator_limits.enabled = ideal.actuator_limits.enabled;
    settings.turbulence = ideal.turbulence;
    settings.discrete_gusts = ideal.discrete_gusts;
    settings.sensor_noise = ideal.sensor_noise;
    settings.servos = ideal.servos;
  }
  const auto set = [](const std::optional<bool>& given, bool& value) {
    if (given) value = *given;
  };
  set(controls.parameter_uncertainty, settings.parameter_uncertainty);
  set(controls.wind_gust, settings.wind_gust.enabled);
  set(controls.measurement_noise, settings.noise.measurement);
  set(controls.actuator_noise, settings.noise.actuator);
  set(controls.wind_noise, settings.noise.wind_component);
  set(controls.induced_velocity_noise, settings.noise.induced_velocity);
  set(controls.actuator_limits, settings.actuator_limits.enabled);
  set(controls.anti_windup, settings.actuator_limits.anti_windup);
  const auto scale = [](const char* name, const std::optional<double>& given, double& value) {
    if (!given) return;
    if (!(*given >= 0.0) || !std::isfinite(*given))
      throw Error(std::string(name) + " " + std::to_string(*given) + ": must be finite and >= 0");
    value = *given;
  };
  scale("uncertainty_scale", controls.uncertainty_scale, settings.uncertainty_scale);
  heli::check_uncertainty_scale(settings.uncertainty_scale);
  if (controls.parameter_deviations) {
    heli::parameter_draw(*controls.parameter_deviations);
    settings.parameter_deviations = *controls.parameter_deviations;
  }
  scale("noise_scale", controls.noise_scale, settings.noise.scale);
  scale("gust_scale", controls.gust_scale, settings.wind_gust.amplitude_scale);
  if (controls.gust_onset) {
    if (!(*controls.gust_onset >= 0.0) || !std::isfinite(*controls.gust_onset))
      throw Error("gust_onset " + seconds(*controls.gust_onset) + ": must be finite and >= 0");
    settings.wind_gust.onset = *controls.gust_onset;
  }
  controls.beyond_paper.apply(settings);
  if (controls.turbulence_model) settings.turbulence.model = *controls.turbulence_model;
  if (controls.turbulence_intensity) settings.turbulence.intensity = *controls.turbulence_intensity;
  scale("turbulence_scale", controls.turbulence_scale, settings.turbulence.scale);
  if (controls.servo_delay_samples) settings.servos.delay_samples = *controls.servo_delay_samples;
  if (controls.servo_time_constant) settings.servos.time_constant.setConstant(*controls.servo_time_constant);
  if (controls.slowdown) {
    using Latency = sim::FlightComputerSettings::Latency;
    if (settings.computer.latency != Latency::measured && settings.computer.latency != Latency::step_time)
      throw Error("slowdown: only for a flight computer whose latency is measured or step-time (the scenario's "
                  "simulation.computer, docs/model.md §15.7)");
    settings.computer.slowdown = *controls.slowdown;
  }
  if (controls.summary_only) settings.keep_log = !*controls.summary_only;
  if (controls.timing) settings.measure_compute_time = *controls.timing;
  // Every override given, the whole checked together (e.g. the log of a long flight must fit).
  settings.validate();
}

Eigen::VectorXd offset_initial_state(const RunControls& controls, const Eigen::VectorXd& initial_state) {
  Eigen::VectorXd x = initial_state;
  if (controls.initial_offset) {
    if (!controls.initial_offset->allFinite()) throw Error("initial_offset: every entry must be finite");
    x.segment<3>(heli::kXp) += *controls.initial_offset;
  }
  if (controls.initial_attitude_offset) {
    if (!controls.initial_attitude_offset->allFinite())
      throw Error("initial_attitude_offset: every entry must be finite");
    x.segment<3>(heli::kPhi) += *controls.initial_attitude_offset;
  }
  return x;
}

Scenario as_flown(const RunControls& controls, const Scenario& scenario) {
  const Scenario faster = controls.speed_scale ? scenario.at_speed(*controls.speed_scale) : scenario;
  return controls.course ? faster.turned(*controls.course) : faster;
}

}  // namespace thetad
