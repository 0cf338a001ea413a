// The rows of the run settings' table (settings/run_settings.hpp).
#include "settings/run_settings.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/fixed_string.hpp"
#include "core/helicopter/uncertainty.hpp"
#include "core/sim/seed.hpp"
#include "settings/disturbance_json.hpp"
#include "settings/plant_setting_rows.hpp"
#include "settings/run_setting_kinds.hpp"

namespace thetad {

namespace {

using Json = nlohmann::ordered_json;
using Value = RunSetting::Value;
using Option = RunSetting::Option;
constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;

std::string seconds(double value) {
  std::ostringstream text;
  text.precision(12);
  text << value << " s";
  return text.str();
}

// The initial offsets are vectors in RunControls; a campaign sweeps their axes one by one, the
// attitude's in degrees (as people state angles), flown in radians.
void offset_axis(std::optional<Eigen::Vector3d>& offset, int axis, double value) {
  if (!offset) offset = Eigen::Vector3d::Zero();
  (*offset)[axis] = value;
}

Eigen::Vector3d vector3(const Json& entries) { return Eigen::Vector3d(entries.get<std::array<double, 3>>().data()); }

// One row per run setting. The order is the order they act on the flight's settings (the ideal
// switch before the disturbances it turns off, the scenario's disturbance blocks before the single
// fields of them) and the order a result's "settings" records them.
std::vector<RunSetting> table() {
  using Settings = sim::SimulationSettings;
  std::vector<RunSetting> rows = {
      {.name = "ideal", .value = Value::on_off,
       .description = "no parameter uncertainty, noise, wind or actuator limits (before every other setting)",
       .apply = [](double v, RunControls& c) { c.ideal = switch_value(v); },
       .example = "1", .option = "--ideal", .option_form = Option::on_when_given,
       .fly = [](const RunControls& c, Settings& s) {
         if (!c.ideal) return;
         const Settings ideal = Settings::ideal();
         s.parameter_uncertainty = ideal.parameter_uncertainty;
         s.wind_gust.enabled = ideal.wind_gust.enabled;
         s.noise = ideal.noise;
         s.actuator_limits.enabled = ideal.actuator_limits.enabled;
         s.turbulence = ideal.turbulence;
         s.discrete_gusts = ideal.discrete_gusts;
         s.sensor_noise = ideal.sensor_noise;
         s.servos = ideal.servos;
       }},
      {.name = "seed", .value = Value::seed,
       .description = "seed of the run's random numbers (default: the scenario's, else 1)",
       .parse = [](const std::string& text, RunControls& c) {
         const std::optional<std::uint64_t> seed = sim::parse_seed(text);
         if (!seed) throw Error("'" + text + "': " + std::string(sim::kSeedExpected));
         c.seed = *seed;
       },
       .example = "7", .option = "--seed", .option_form = Option::value,
       .fly = [](const RunControls& c, Settings& s) { if (c.seed) s.seed = *c.seed; },
       .result_key = "provenance.seed",
       .replay = [](const Json& v, RunControls& c) { c.seed = v.get<std::uint64_t>(); },
       .file_key = "simulation.seed",
       .read = [](const FileField& f, RunControls& c) { if (f.block.has(f.key)) c.seed = f.block.seed(f.key, 1); }},
      {.name = "dt_s", .value = Value::number, .unit = "s",
       .description = "plant (RK4) step; must divide the controller period (1 ms)", .min = 0.0,
       .apply = [](double v, RunControls& c) { c.dt = v; }, .factor_column = 20, .earlier_name = "dt",
       .example = "0.0005", .option = "--dt", .option_form = Option::value,
       .fly = [](const RunControls& c, Settings& s) {
         if (!c.dt) return;
         const double dt = *c.dt;
         if (!(dt > 0.0) || !std::isfinite(dt)) throw Error("dt " + seconds(dt) + ": must be > 0");
         // A file's pair: dt as given, and the next row sets the steps.
         if (c.controller_period_steps) {
           s.dt = dt;
           return;
         }
         // The controller keeps sampling at the scenario's period with zero-order hold.
         const double period = s.controller_period();
         const double steps = std::round(period / dt);
         if (steps < 1.0 || std::abs(steps * dt - period) > 1e-9 * period)
           throw Error("dt " + seconds(dt) + " does not divide the controller period " + seconds(period) +
                       ": the controller samples every " + seconds(period) +
                       " with zero-order hold, so the plant step must be that period divided by a whole number");
         s.dt = period / steps;
         s.controller_period_steps = static_cast<int>(steps);
       },
       .record = [](const Settings& s, Json& j) { j["dt_s"] = s.dt; },
       .result_key = "settings.dt_s", .replay = [](const Json& v, RunControls& c) { c.dt = v.get<double>(); },
       .file_key = "simulation.dt", .read = read_dt},
      {.name = "controller_period_s", .unit = "s", .description = "T_c = dt · controller_period_steps (a scenario's)",
       .fly = [](const RunControls& c, Settings& s) {
         if (c.controller_period_steps) s.controller_period_steps = *c.controller_period_steps;
       },
       .record = [](const Settings& s, Json& j) {
         j["controller_period_steps"] = s.controller_period_steps;
         j["controller_period_s"] = s.controller_period();
       },
       .file_key = "simulation.controller_period_steps", .read = read_count<&RunControls::controller_period_steps, 1>},
      {.name = "log_every", .value = Value::whole, .description = "log every N-th controller sample (default 1)",
       .min = 1.0, .max = std::numeric_limits<int>::max(),
       .apply = [](double v, RunControls& c) { c.log_every = whole(v); },
       .example = "10", .option = "--log-every", .option_form = Option::value, .option_writes_runs = true,
       .fly = [](const RunControls& c, Settings& s) {
         if (!c.log_every) return;
         if (*c.log_every < 1) throw Error("log_every " + std::to_string(*c.log_every) + ": must be >= 1");
         s.log_every = *c.log_every;
       },
       .record = [](const Settings& s, Json& j) { j["log_every"] = s.log_every; },
       .result_key = "settings.log_every", .replay = [](const Json& v, RunControls& c) { c.log_every = v.get<int>(); },
       .file_key = "simulation.log_every", .read = read_count<&RunControls::log_every, 1>},
      {.name = "summary_only", .value = Value::on_off,
       .description = "write no log (CSV), only the result JSON (complete summary)",
       .apply = [](double v, RunControls& c) { c.summary_only = switch_value(v); },
       .example = "1", .option = "--summary-only", .option_form = Option::on_when_given, .option_writes_runs = true,
       .fly = [](const RunControls& c, Settings& s) { if (c.summary_only) s.keep_log = !*c.summary_only; },
       .record = [](const Settings& s, Json& j) { j["summary_only"] = !s.keep_log; },
       .result_key = "settings.summary_only",
       .replay = [](const Json& v, RunControls& c) { c.summary_only = v.get<bool>(); },
       .file_key = "simulation.summary_only", .read = read_switch<&RunControls::summary_only>},
      {.name = "duration_s", .value = Value::number, .unit = "s",
       .description = "simulated seconds to fly (default: the scenario's; shorter: the flight stops there)", .min = 0.0,
       .max = Settings::kMaxDuration, .apply = [](double v, RunControls& c) { c.duration = v; }, .factor_column = 21,
       .earlier_name = "duration", .example = "3", .option = "--duration", .option_form = Option::value,
       .fly = [](const RunControls& c, Settings& s) {
         if (!c.duration) return;
         if (!(*c.duration > 0.0) || !(*c.duration <= Settings::kMaxDuration))
           throw Error("duration " + seconds(*c.duration) + ": must be > 0 and at most 86400 s (one simulated day)");
         s.duration = *c.duration;
       },
       .record = [](const Settings& s, Json& j) { j["duration_s"] = s.duration; },
       .result_key = "settings.duration_s", .replay = [](const Json& v, RunControls& c) { c.duration = v.get<double>(); },
       .file_key = "duration, simulation.duration", .read = read_duration},
      switch_row<&RunControls::parameter_uncertainty, &Settings::parameter_uncertainty>(
          {.name = "parameter_uncertainty", .description = "Table 1's parameters drawn (docs/model.md §9.1)",
           .example = "0",
           .record = [](const Settings& s, Json& j) { j["parameter_uncertainty"] = s.parameter_uncertainty; },
           .result_key = "settings.parameter_uncertainty",
           .file_key = "simulation.disturbances.parameter_uncertainty"}),
      scale_row<"uncertainty_scale", &RunControls::uncertainty_scale, &Settings::uncertainty_scale>(
          {.description = "multiplies Table 1's 21 parameter bounds (0 nominal plant, 1 the paper's, 2 twice)",
           .max = 9.99, .factor_column = 1, .example = "0.5",
           .record = [](const Settings& s, Json& j) { j["uncertainty_scale"] = s.uncertainty_scale; },
           .result_key = "settings.uncertainty_scale",
           // Results written before the disturbance scales existed flew at the paper's strengths.
           .absent_until = 1, .before = [](RunControls& c) { c.uncertainty_scale = 1.0; }}),
      {.name = "parameter_deviations",
       .description = "Table 1's 21 parameter deviations xi in [-1, 1] instead of the draw (a worst case)",
       .fly = [](const RunControls& c, Settings& s) {
         if (!c.parameter_deviations) return;
         heli::parameter_draw(*c.parameter_deviations);
         s.parameter_deviations = *c.parameter_deviations;
       },
       // In table order, only when fixed instead of drawn.
       .record = [](const Settings& s, Json& j) {
         if (!s.parameter_deviations.empty()) j["parameter_deviations"] = s.parameter_deviations;
       },
       .result_key = "settings.parameter_deviations",
       .replay = [](const Json& v, RunControls& c) { c.parameter_deviations = v.get<std::vector<double>>(); },
       .absent_until = RunSetting::kEveryVersion, .file_key = "simulation.disturbances.parameter_deviations",
       .read = read_parameter_deviations},
      switch_row<&RunControls::wind_gust, &Settings::wind_gust, &sim::WindGustSettings::enabled>(
          {.name = "wind_gust", .description = "the paper's wind: mean and gust (Table 1 #22-25)", .example = "0",
           .record = [](const Settings& s, Json& j) {
             j["wind_gust"] = {{"enabled", s.wind_gust.enabled},
                               {"model", s.wind_gust.model == sim::WindGustSettings::Model::held_white
                                             ? "held_white"
                                             : "gauss_markov"},
                               {"sigma_m_per_s", s.wind_gust.sigma},
                               {"correlation_time_s", s.wind_gust.correlation_time}};
           },
           .result_key = "settings.wind_gust.enabled",
           .file_key = "simulation.disturbances.wind_gust"}),
      scale_row<"gust_scale", &RunControls::gust_scale, &Settings::wind_gust, &sim::WindGustSettings::amplitude_scale>(
          {.description = "multiplies the whole wind, mean and gust (0 calm, 1 the paper's gust)", .factor_column = 2,
           .example = "0.5",
           .record = [](const Settings& s, Json& j) { j["gust_scale"] = s.wind_gust.amplitude_scale; },
           .result_key = "settings.gust_scale",
           .absent_until = 1, .before = [](RunControls& c) { c.gust_scale = 1.0; }}),
      {.name = "gust_onset_s", .value = Value::number, .unit = "s",
       .description = "time the wind starts blowing (calm air before)", .min = 0.0,
       .apply = [](double v, RunControls& c) { c.gust_onset = v; }, .factor_column = 3, .earlier_name = "gust_onset",
       .example = "2",
       .fly = [](const RunControls& c, Settings& s) {
         if (!c.gust_onset) return;
         if (!(*c.gust_onset >= 0.0) || !std::isfinite(*c.gust_onset))
           throw Error("gust_onset " + seconds(*c.gust_onset) + ": must be finite and >= 0");
         s.wind_gust.onset = *c.gust_onset;
       },
       .record = [](const Settings& s, Json& j) { j["gust_onset_s"] = s.wind_gust.onset; },
       .result_key = "settings.gust_onset_s",
       .replay = [](const Json& v, RunControls& c) { c.gust_onset = v.get<double>(); },
       .absent_until = 1, .before = [](RunControls& c) { c.gust_onset = 0.0; }},
      switch_row<&RunControls::measurement_noise, &Settings::noise, &sim::NoiseSettings::measurement>(
          {.name = "measurement_noise", .description = "the sensors' noise (Table 1 #31-42)", .example = "0",
           // The noise block: this row's switch and those of the rows after it.
           .record = [](const Settings& s, Json& j) {
             j["noise"] = {{"measurement", s.noise.measurement},
                           {"measurement_on", s.noise.measurement_on == sim::MeasurementNoiseOn::feedback_signal
                                                  ? "feedback_signal"
                                                  : "absolute_state"},
                           {"actuator", s.noise.actuator},
                           {"wind_component", s.noise.wind_component},
                           {"induced_velocity", s.noise.induced_velocity},
                           {"scale", s.noise.scale}};
           },
           .result_key = "settings.noise.measurement",
           .file_key = "simulation.disturbances.measurement_noise"}),
      {.name = "measurement_noise_on",
       .description = "what the sensors' noise is added to: feedback_signal (the default) or absolute_state "
                      "(docs/model.md §9.3); recorded in the noise block",
       .fly = [](const RunControls& c, Settings& s) {
         if (c.measurement_noise_on) s.noise.measurement_on = *c.measurement_noise_on;
       },
       .file_key = "simulation.disturbances.measurement_noise_on",
       .read = read_measurement_noise_on},
      switch_row<&RunControls::actuator_noise, &Settings::noise, &sim::NoiseSettings::actuator>(
          {.name = "actuator_noise", .description = "the actuators' noise (Table 1 #43-47)", .example = "0",
           .result_key = "settings.noise.actuator",
           .file_key = "simulation.disturbances.actuator_noise"}),
      switch_row<&RunControls::wind_noise, &Settings::noise, &sim::NoiseSettings::wind_component>(
          {.name = "wind_noise", .description = "the wind components' noise (Table 1 #26-28)", .example = "0",
           .result_key = "settings.noise.wind_component",
           .file_key = "simulation.disturbances.wind_noise"}),
      switch_row<&RunControls::induced_velocity_noise, &Settings::noise, &sim::NoiseSettings::induced_velocity>(
          {.name = "induced_velocity_noise", .description = "the induced velocities' noise (Table 1 #29-30)",
           .example = "0",
           .result_key = "settings.noise.induced_velocity",
           .file_key = "simulation.disturbances.induced_velocity_noise"}),
      scale_row<"noise_scale", &RunControls::noise_scale, &Settings::noise, &sim::NoiseSettings::scale>(
          {.description = "multiplies every sensor, actuator, wind-component and induced-velocity noise level",
           .factor_column = 4, .example = "0.5",
           .result_key = "settings.noise.scale",
           .absent_until = 1, .before = [](RunControls& c) { c.noise_scale = 1.0; }}),
      {.name = "divergence_limits", .description = "where a flight is declared diverged (a record only)",
       .record = [](const Settings& s, Json& j) {
         j["divergence_limits"] = {{"max_attitude_rad", s.limits.max_attitude},
                                   {"max_body_rate_rad_per_s", s.limits.max_body_rate},
                                   {"max_speed_m_per_s", s.limits.max_speed},
                                   {"max_ground_penetration_m", s.limits.max_ground_penetration}};
       }},
      switch_row<&RunControls::actuator_limits, &Settings::actuator_limits, &sim::ActuatorLimits::enabled>(
          {.name = "actuator_limits",
           .description = "servo magnitude and rate limits on the applied input (default: the scenario's, else on; "
                          "docs/model.md §12)",
           .factor_column = 13, .example = "0", .option = "--actuator-limits", .option_form = Option::on_off,
           // The limits' block: this row's switch, the anti-windup's, and the bounds.
           .record = [](const Settings& s, Json& j) {
             const auto channels = [](const sim::InputVector& v) { return Json::array({v[0], v[1], v[2], v[3], v[4]}); };
             j["actuator_limits"] = {
                 {"enabled", s.actuator_limits.enabled},
                 {"anti_windup", s.actuator_limits.anti_windup},
                 {"channels", {"T_mr_N", "delta_ped_rad", "delta_col_rad", "delta_lon_rad", "delta_lat_rad"}},
                 {"lower", channels(s.actuator_limits.lower)},
                 {"upper", channels(s.actuator_limits.upper)},
                 {"rate_per_s", channels(s.actuator_limits.rate)}};
           },
           .result_key = "settings.actuator_limits.enabled",
           // Results written before the actuator limits existed flew without them.
           .absent_until = 1, .before = [](RunControls& c) { c.actuator_limits = false; },
           .file_key = "simulation.actuator_limits"}),
      switch_row<&RunControls::anti_windup, &Settings::actuator_limits, &sim::ActuatorLimits::anti_windup>(
          {.name = "anti_windup",
           .description = "with the actuator limits, hold the position-error integrals at samples where a limit acts "
                          "(default: the scenario's, else on; docs/model.md §12)",
           .example = "0", .option = "--anti-windup", .option_form = Option::on_off,
           .result_key = "settings.actuator_limits.anti_windup",
           // Results written before the anti-windup existed flew without it.
           .absent_until = 2, .before = [](RunControls& c) { c.anti_windup = false; },
           .file_key = "simulation.anti_windup"}),
      {.name = "beyond_paper",
       .description = "the disturbances beyond the paper and the flight computer (docs/model.md §15), whole blocks",
       .fly = [](const RunControls& c, Settings& s) { c.beyond_paper.apply(s); },
       .record = [](const Settings& s, Json& j) { write_beyond_paper(s, j); },
       // read_beyond_paper: a block that a result lacks was not there when it was written (the four
       // disturbances before format_version 3, the computer before the flight computer existed):
       // the run flew without it, so its replay does too.
       .result_key = "settings",
       .replay = [](const Json& v, RunControls& c) { c.beyond_paper = read_beyond_paper(v); },
       .file_key = "simulation.wind, simulation.sensor_noise, simulation.servos, simulation.computer",
       .read = [](const FileField& f, RunControls& c) { c.beyond_paper = read_disturbance_blocks(f.block, f.folder); }},
      {.name = "turbulence_model", .value = Value::choice,
       .description = "the gust model on the paper's mean wind (docs/model.md §15): paper, dryden, gauss_markov",
       .min = 0.0, .max = 2.0, .choices = "paper dryden gauss_markov",
       .apply = [](double v, RunControls& c) {
         c.turbulence_model = static_cast<sim::TurbulenceSettings::Model>(whole(v));
       }, .factor_column = 14, .example = "dryden",
       .fly = [](const RunControls& c, Settings& s) { if (c.turbulence_model) s.turbulence.model = *c.turbulence_model; },
       .file_key = "simulation.wind.model"},
      {.name = "turbulence_intensity", .value = Value::choice,
       .description = "the Dryden intensity: light, moderate, severe (W20 = 15, 30, 45 kt)", .min = 0.0, .max = 2.0,
       .choices = "light moderate severe",
       .apply = [](double v, RunControls& c) {
         c.turbulence_intensity = static_cast<sim::TurbulenceIntensity>(whole(v));
       }, .factor_column = 15, .example = "severe",
       .fly = [](const RunControls& c, Settings& s) {
         if (c.turbulence_intensity) s.turbulence.intensity = *c.turbulence_intensity;
       },
       .file_key = "simulation.wind.intensity"},
      scale_row<"turbulence_scale", &RunControls::turbulence_scale, &Settings::turbulence,
                &sim::TurbulenceSettings::scale>(
          {.description = "multiplies the Dryden or Gauss-Markov turbulence (0 none, 1 as specified)",
           .factor_column = 16, .example = "0.5",
           .file_key = "simulation.wind.scale"}),
      {.name = "servo_delay_samples", .value = Value::whole, .unit = "samples",
       .description = "transport delay of the command, in controller samples", .min = 0.0,
       .max = sim::ServoSettings::kMaxDelaySamples,
       .apply = [](double v, RunControls& c) { c.servo_delay_samples = whole(v); },
       .factor_column = 17, .earlier_name = "servo_delay", .example = "2",
       .fly = [](const RunControls& c, Settings& s) {
         if (c.servo_delay_samples) s.servos.delay_samples = *c.servo_delay_samples;
       },
       .file_key = "simulation.servos.delay_samples"},
      {.name = "servo_time_constant_s", .value = Value::number, .unit = "s",
       .description = "first-order servo lag of every input", .min = 0.0, .max = 10.0,
       .apply = [](double v, RunControls& c) { c.servo_time_constant = v; }, .factor_column = 18,
       .earlier_name = "servo_time_constant", .example = "0.02",
       .fly = [](const RunControls& c, Settings& s) {
         if (c.servo_time_constant) s.servos.time_constant.setConstant(*c.servo_time_constant);
       },
       .file_key = "simulation.servos.time_constant"},
      {.name = "slowdown", .value = Value::number,
       .description = "the flight computer this many times slower than its step times (docs/model.md §15.7; the "
                      "scenario's computer latency measured or step-time)",
       .min = 0.0, .max = sim::FlightComputerSettings::kMaxSlowdown,
       .apply = [](double v, RunControls& c) { c.slowdown = v; }, .factor_column = 19, .example = "30",
       .fly = [](const RunControls& c, Settings& s) {
         if (!c.slowdown) return;
         using Latency = sim::FlightComputerSettings::Latency;
         if (s.computer.latency != Latency::measured && s.computer.latency != Latency::step_time)
           throw Error("slowdown: only for a flight computer whose latency is measured or step-time (the scenario's "
                       "simulation.computer, docs/model.md §15.7)");
         s.computer.slowdown = *c.slowdown;
       },
       .file_key = "simulation.computer.slowdown"},
      {.name = "timing", .value = Value::on_off,
       .description = "wall-clock time measured (the in-flight step times, host and start time); without it, reruns "
                      "with the same seed give byte-identical files",
       .apply = [](double v, RunControls& c) { c.timing = switch_value(v); },
       .example = "0", .option = "--no-timing", .option_form = Option::off_when_given, .option_writes_runs = true,
       .fly = [](const RunControls& c, Settings& s) { if (c.timing) s.measure_compute_time = *c.timing; },
       .record = [](const Settings& s, Json& j) { j["timing"] = s.measure_compute_time; },
       .result_key = "settings.timing", .replay = [](const Json& v, RunControls& c) { c.timing = v.get<bool>(); },
       .file_key = "simulation.timing", .read = read_switch<&RunControls::timing>},
      // What acts on the scenario and its initial state (Flight), recorded in the provenance.
      {.name = "initial_offset_x_m", .value = Value::number, .unit = "m",
       .description = "added to the initial north position",
       .apply = [](double v, RunControls& c) { offset_axis(c.initial_offset, 0, v); }, .factor_column = 5,
       .earlier_name = "initial_offset_x", .example = "0.5"},
      {.name = "initial_offset_y_m", .value = Value::number, .unit = "m",
       .description = "added to the initial east position",
       .apply = [](double v, RunControls& c) { offset_axis(c.initial_offset, 1, v); }, .factor_column = 6,
       .earlier_name = "initial_offset_y", .example = "-0.5"},
      {.name = "initial_offset_z_m", .value = Value::number, .unit = "m",
       .description = "added to the initial down position (negative: higher)",
       .apply = [](double v, RunControls& c) { offset_axis(c.initial_offset, 2, v); }, .factor_column = 7,
       .earlier_name = "initial_offset_z", .example = "-1"},
      {.name = "initial_offset_m", .unit = "m", .description = "the initial offsets' vector, north-east-down",
       .result_key = "provenance.initial_offset_m",
       .replay = [](const Json& v, RunControls& c) { c.initial_offset = vector3(v); },
       .absent_until = RunSetting::kEveryVersion},
      {.name = "initial_offset_roll_deg", .value = Value::number, .unit = "deg",
       .description = "added to the initial roll angle phi", .min = -180.0, .max = 180.0,
       .apply = [](double v, RunControls& c) { offset_axis(c.initial_attitude_offset, 0, v * kRadiansPerDegree); },
       .factor_column = 8, .earlier_name = "initial_offset_roll", .example = "5"},
      {.name = "initial_offset_pitch_deg", .value = Value::number, .unit = "deg",
       .description = "added to the initial pitch angle theta", .min = -180.0, .max = 180.0,
       .apply = [](double v, RunControls& c) { offset_axis(c.initial_attitude_offset, 1, v * kRadiansPerDegree); },
       .factor_column = 9, .earlier_name = "initial_offset_pitch", .example = "-5"},
      {.name = "initial_offset_yaw_deg", .value = Value::number, .unit = "deg",
       .description = "added to the initial yaw angle psi (heading)", .min = -180.0, .max = 180.0,
       .apply = [](double v, RunControls& c) { offset_axis(c.initial_attitude_offset, 2, v * kRadiansPerDegree); },
       .factor_column = 10, .earlier_name = "initial_offset_yaw", .example = "30"},
      {.name = "initial_attitude_offset_rad", .unit = "rad",
       .description = "the attitude offsets' vector: roll, pitch, yaw",
       .result_key = "provenance.initial_attitude_offset_rad",
       .replay = [](const Json& v, RunControls& c) { c.initial_attitude_offset = vector3(v); },
       .absent_until = RunSetting::kEveryVersion},
      {.name = "trajectory_speed_scale", .value = Value::number,
       .description = "flies the same path this many times faster (the scenario's duration / s)", .min = 0.01,
       .max = 100.0, .apply = [](double v, RunControls& c) { c.speed_scale = v; }, .factor_column = 11,
       .example = "1.5", .result_key = "provenance.trajectory_speed_scale",
       .replay = [](const Json& v, RunControls& c) { c.speed_scale = v.get<double>(); },
       .absent_until = RunSetting::kEveryVersion},
      {.name = "course", .value = Value::number, .unit = "deg",
       .description = "turns the scenario's trajectory about its start, north towards east (the heading stays)",
       .min = -360.0, .max = 360.0, .apply = [](double v, RunControls& c) { c.course = v * kRadiansPerDegree; },
       .factor_column = 12, .example = "30", .result_key = "provenance.course_rad",
       .replay = [](const Json& v, RunControls& c) { c.course = v.get<double>(); },
       .absent_until = RunSetting::kEveryVersion},
  };
  // A plant's own, which act on its settings and initial state (Flight), last.
  for (RunSetting& row : plant_setting_rows()) rows.push_back(std::move(row));
  return rows;
}

}  // namespace

const std::vector<RunSetting>& run_settings() {
  static const std::vector<RunSetting> all = table();
  return all;
}

}  // namespace thetad
