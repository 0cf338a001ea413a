#include "core/sim/simulator.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <utility>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "core/helicopter/uncertainty.hpp"
#include "core/sim/rk4.hpp"
#include "core/sim/run_metrics.hpp"

namespace thetad::sim {

namespace {

using heli::kInputDim;
using heli::kStateDim;

struct NameUnit {
  const char* name;
  const char* unit;
};

// Names and units of the 18 states and the 5 inputs, in index order (spec §1.4).
constexpr std::array<NameUnit, kStateDim> kStateColumns = {{
    {"x_p", "m"}, {"y_p", "m"}, {"z_p", "m"},
    {"u", "m_per_s"}, {"v", "m_per_s"}, {"w", "m_per_s"},
    {"phi", "rad"}, {"theta", "rad"}, {"psi", "rad"},
    {"p", "rad_per_s"}, {"q", "rad_per_s"}, {"r", "rad_per_s"},
    {"a1", "rad"}, {"b1", "rad"},
    {"x_i", "m_s"}, {"y_i", "m_s"}, {"z_i", "m_s"},
    {"s", "unitless"},
}};
constexpr std::array<NameUnit, kInputDim> kInputColumns = {{
    {"T_mr", "N"}, {"delta_ped", "rad"}, {"delta_col", "rad"}, {"delta_lon", "rad"}, {"delta_lat", "rad"},
}};

std::vector<LogColumn> build_log_schema() {
  // The row writer in simulate() appends the blocks in this order.
  std::vector<LogColumn> columns{{"t", "s"}, {"x_c", "m"}, {"y_c", "m"}, {"z_c", "m"}};
  for (const auto& [name, unit] : kStateColumns) columns.push_back({name, unit});
  for (const auto& [name, unit] : kStateColumns) columns.push_back({std::string("meas_") + name, unit});
  for (const auto& [name, unit] : kInputColumns) columns.push_back({std::string("cmd_") + name, unit});
  for (const auto& [name, unit] : kInputColumns) columns.push_back({std::string("app_") + name, unit});
  // 0 free, 1 held at a magnitude bound, 2 slowed by the rate limit (ActuatorLimiter).
  for (const auto& [name, unit] : kInputColumns) columns.push_back({std::string("sat_") + name, "flag"});
  columns.push_back({"Omega_mr", "rad_per_s"});
  columns.push_back({"wind_N", "m_per_s"});
  columns.push_back({"wind_E", "m_per_s"});
  columns.push_back({"wind_D", "m_per_s"});
  columns.push_back({"compute", "ns"});
  return columns;
}

std::string format_reason(const char* what, double value, double limit, const char* unit, double t) {
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "%s = %.6g %s exceeds %.6g %s at t = %.4f s", what, value, unit,
                limit, unit, t);
  return buffer;
}

// Why the state x at time t counts as diverged, or nothing.
std::optional<std::string> divergence(const Eigen::VectorXd& x, const DivergenceLimits& limits, double t) {
  using namespace heli;
  if (!x.allFinite()) {
    char buffer[80];
    std::snprintf(buffer, sizeof buffer, "non-finite state at t = %.4f s", t);
    return buffer;
  }
  if (std::abs(x[kPhi]) > limits.max_attitude)
    return format_reason("roll |phi|", std::abs(x[kPhi]), limits.max_attitude, "rad", t);
  if (std::abs(x[kTheta]) > limits.max_attitude)
    return format_reason("pitch |theta|", std::abs(x[kTheta]), limits.max_attitude, "rad", t);
  const char* rate_names[] = {"roll rate |p|", "pitch rate |q|", "yaw rate |r|"};
  for (int i = 0; i < 3; ++i) {
    if (std::abs(x[kP + i]) > limits.max_body_rate)
      return format_reason(rate_names[i], std::abs(x[kP + i]), limits.max_body_rate, "rad/s", t);
  }
  const double speed = x.segment<3>(kU).norm();
  if (speed > limits.max_speed) return format_reason("speed |(u, v, w)|", speed, limits.max_speed, "m/s", t);
  if (x[kZp] > limits.max_ground_penetration)
    return format_reason("ground penetration z_p", x[kZp], limits.max_ground_penetration, "m", t);
  return std::nullopt;
}

std::string failure_reason(const char* source, const std::exception& error, double t) {
  char buffer[80];
  std::snprintf(buffer, sizeof buffer, "%s failed at t = %.4f s: ", source, t);
  return buffer + std::string(error.what());
}

// Reserves the log for the whole run, so that the step loop allocates nothing (its size was
// bounded by validate()).
void reserve_log(const SimulationSettings& settings, std::int64_t samples, RunLog& log) {
  const std::int64_t rows = settings.keep_log ? (samples + settings.log_every - 1) / settings.log_every : 0;
  log.values.reserve(static_cast<std::size_t>(rows) * log_schema().size());
}

// What a run's summary says before it flies: the law, the settings, the model's switches and the
// drawn Table 1 parameter factors (none without parameter uncertainty).
void describe_run(const ControlLaw& law, const SimulationSettings& settings, const heli::ModelOptions& options,
                  const heli::PerturbedParameters& drawn, RunSummary& summary) {
  summary.controller = law.name();
  summary.settings = settings;
  summary.model_options = options.to_string();
  if (!settings.parameter_uncertainty) return;
  for (const auto& entry : drawn.report) {
    if (entry.category == heli::UncertaintyCategory::parameter)
      summary.parameter_factors.emplace_back(entry.name, entry.factor);
  }
}

// V_track of Eq. 36 on the true state, for the cost. Fixed-size pieces: a comma initializer taking
// the Vector3d would instantiate an 8-wide packet copy that GCC 12 flags (-Warray-bounds) under
// -march=native.
void true_tracking_vector(const Eigen::VectorXd& x, const Eigen::Vector3d& error, const Eigen::Vector3d& integral,
                          Eigen::VectorXd& v_track) {
  using namespace heli;
  v_track.segment<3>(kXp) = error;
  v_track.segment<11>(kU) = x.segment<11>(kU);
  v_track.segment<3>(kXi) = integral;
  v_track(kS) = 1.0;
}

// control() of `law`; its wall time (ns) when `timing`, else 0.
std::int64_t call_control(ControlLaw& law, double t, const Eigen::VectorXd& measured, const Reference& reference,
                          Eigen::VectorXd& command, bool timing) {
  if (!timing) {
    law.control(t, measured, reference, command);
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  law.control(t, measured, reference, command);
  const auto stop = std::chrono::steady_clock::now();
  return std::chrono::duration_cast<std::chrono::nanoseconds>(stop - start).count();
}

// The controller period's RK4 steps from t with `applied` held (zero-order hold). On divergence,
// t becomes the end of the step that diverged and the reason is returned.
std::optional<std::string> hold_for_one_period(const heli::Helicopter& plant, const Eigen::VectorXd& applied,
                                               const SimulationSettings& settings, Rk4Workspace& workspace,
                                               Eigen::VectorXd& x, double& t) {
  for (int step = 1; step <= settings.controller_period_steps; ++step) {
    const double t_end = t + step * settings.dt;
    std::optional<std::string> failure;
    try {
      rk4_step(plant, applied, settings.dt, workspace, x);
      failure = divergence(x, settings.limits, t_end);
    } catch (const Error& error) {
      failure = failure_reason("plant", error, t_end);
    }
    if (failure) {
      t = t_end;
      return failure;
    }
  }
  return std::nullopt;
}

// One log row, in the order of log_schema().
void append_row(double t, const Eigen::Vector3d& command_position, const Eigen::VectorXd& x,
                const Eigen::VectorXd& measured, const Eigen::VectorXd& command, const Eigen::VectorXd& applied,
                unsigned saturation_flags, double rotor_speed, const Eigen::Vector3d& wind, std::int64_t compute_ns, RunLog& log) {
  auto& row = log.values;
  row.push_back(t);
  row.insert(row.end(), command_position.begin(), command_position.end());
  row.insert(row.end(), x.begin(), x.end());
  row.insert(row.end(), measured.begin(), measured.end());
  row.insert(row.end(), command.begin(), command.end());
  row.insert(row.end(), applied.begin(), applied.end());
  for (int k = 0; k < kInputDim; ++k) {
    const bool magnitude = (saturation_flags >> k) & 1u, rate = (saturation_flags >> (k + kInputDim)) & 1u;
    row.push_back(magnitude ? 1.0 : rate ? 2.0 : 0.0);
  }
  row.push_back(rotor_speed);
  row.insert(row.end(), wind.begin(), wind.end());
  row.push_back(static_cast<double>(compute_ns));
}

}  // namespace

void check_run_memory(double bytes, std::int64_t logged_rows) {
  if (bytes <= SimulationSettings::kMaxRunMemory) return;
  char advice[320];
  std::snprintf(advice, sizeof advice,
                "simulate: this flight's log would need %.1f GiB (%lld logged samples), more than the %.0f GiB a run "
                "may hold: log every N-th sample (log_every, --log-every) or only the summary (--summary-only)",
                bytes / (1 << 30), static_cast<long long>(logged_rows), SimulationSettings::kMaxRunMemory / (1 << 30));
  throw Error(advice);
}

const char* status_name(RunStatus status) {
  switch (status) {
    case RunStatus::completed: return "completed";
    case RunStatus::diverged: return "diverged";
    case RunStatus::failed: return "failed";
  }
  return "unknown";
}

void SimulationSettings::validate() const {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw Error("simulate: dt must be positive and finite");
  if (controller_period_steps < 1) throw Error("simulate: controller_period_steps must be at least 1");
  if (log_every < 1) throw Error("simulate: log_every must be at least 1");
  if (!(duration >= controller_period()) || !(duration <= kMaxDuration))
    throw Error("simulate: duration must be at least one controller period and at most " +
                std::to_string(static_cast<int>(kMaxDuration)) + " s (one simulated day)");
  heli::check_uncertainty_scale(uncertainty_scale);
  if (!(noise.scale >= 0.0) || !std::isfinite(noise.scale))
    throw Error("simulate: the noise scale must be finite and non-negative");
  if (duration / controller_period() > 1e10)
    throw Error("simulate: the controller period is too short for the duration (more than 1e10 samples)");
  if (actuator_limits.enabled) actuator_limits.validate();
  // The log is held whole: bounded here, so that a flight too long to log fails before it flies,
  // with advice, instead of with bad_alloc hours in.
  const auto samples = static_cast<std::int64_t>(std::llround(duration / controller_period()));
  const std::int64_t rows = keep_log ? (samples + log_every - 1) / log_every : 0;
  const auto columns = static_cast<std::int64_t>(log_schema().size());
  check_run_memory(8.0 * static_cast<double>(rows * columns + (measure_compute_time ? samples : 0)), rows);
}

SimulationSettings SimulationSettings::paper() {
  SimulationSettings settings;
  settings.actuator_limits.enabled = false;
  return settings;
}

SimulationSettings SimulationSettings::ideal() {
  SimulationSettings settings;
  settings.parameter_uncertainty = false;
  settings.wind_gust.enabled = false;
  settings.noise.measurement = false;
  settings.noise.actuator = false;
  settings.noise.wind_component = false;
  settings.noise.induced_velocity = false;
  settings.actuator_limits.enabled = false;
  return settings;
}

const std::vector<LogColumn>& log_schema() {
  static const std::vector<LogColumn> schema = build_log_schema();
  return schema;
}

RunResult simulate(ControlLaw& law, const ReferenceTrajectory& reference, const Eigen::VectorXd& x0,
                   const SimulationSettings& settings, const heli::Parameters& nominal,
                   const heli::ModelOptions& options, const std::function<void(double t)>& progress) {
  using namespace heli;
  settings.validate();
  if (x0.size() != kStateDim)
    throw Error("simulate: x0 has " + std::to_string(x0.size()) + " entries, the helicopter has " +
                std::to_string(kStateDim));
  const double period = settings.controller_period();
  const auto samples = static_cast<std::int64_t>(std::llround(settings.duration / period));

  std::mt19937_64 rng(settings.seed);
  const PerturbedParameters drawn = perturbed_parameters(nominal, rng, settings.uncertainty_scale);
  Helicopter plant(settings.parameter_uncertainty ? drawn.parameters : nominal, options);
  const NoiseLevels levels = NoiseLevels::from_uncertainty_table(settings.noise.scale);
  WindGust gust(settings.wind_gust, period);
  ActuatorLimiter limiter(settings.actuator_limits, period);
  // J of Eq. (14) with the weights the controllers are designed with (the paper's, Eqs. 33-34).
  const DesignDefaults design = plant.design_defaults();
  RunMetrics metrics(design.state_weights, design.input_weights, period, samples, settings.measure_compute_time);

  RunResult result;
  RunSummary& summary = result.summary;
  describe_run(law, settings, options, drawn, summary);
  reserve_log(settings, samples, result.log);

  Eigen::VectorXd x = x0;
  Eigen::VectorXd measured(kStateDim), command(kInputDim), applied(kInputDim), v_track(kStateDim);
  Rk4Workspace workspace(kStateDim);
  SampleDraws draws;
  PositionIntegral reference_integral, measured_integral, true_error_integral;

  std::optional<std::string> failure = divergence(x, settings.limits, 0.0);
  bool controller_failed = false;
  try {
    law.reset(x0, 0.0);
  } catch (const std::exception& error) {
    failure = failure_reason("controller", error, 0.0);
    controller_failed = true;
  }
  double t = 0.0;
  for (std::int64_t k = 0; k < samples && !failure; ++k) {
    t = static_cast<double>(k) * period;
    if (progress && k % kProgressSamples == 0) progress(t);
    draws.draw(rng);
    const Eigen::Vector3d wind = gust.sample(t, x[kZp], draws.gust);
    plant.set_environment(sample_environment(wind, draws, levels, settings.noise));
    const Eigen::Vector3d position_command = reference.position(t);
    measure(x, position_command, measured_integral.value, draws, levels, settings.noise, measured);

    std::int64_t elapsed_ns = 0;
    try {
      elapsed_ns = call_control(law, t, measured, Reference{position_command, reference_integral.value}, command,
                                settings.measure_compute_time);
      if (!command.allFinite()) throw Error("non-finite command");
    } catch (const std::exception& error) {
      // Whatever a user's controller throws (a plug-in's own exception types too) ends this run,
      // not the program: the other runs of a comparison go on.
      failure = failure_reason("controller", error, t);
      controller_failed = true;
      break;
    }
    apply_actuator_noise(command, draws, levels, settings.noise, applied);
    limiter.apply(applied);
    double rotor_speed = 0.0;
    try {
      rotor_speed = plant.rotor_speed(x, applied[kTmr]);
    } catch (const Error& error) {
      failure = failure_reason("plant rotor speed", error, t);
      break;
    }

    const Eigen::Vector3d error = x.segment<3>(kXp) - position_command;
    true_tracking_vector(x, error, true_error_integral.value, v_track);
    metrics.add(error, v_track, command, elapsed_ns);
    if (settings.keep_log && k % settings.log_every == 0)
      append_row(t, position_command, x, measured, command, applied, limiter.last_flags(), rotor_speed, plant.environment().wind_ned,
                 elapsed_ns, result.log);

    reference_integral.accumulate(position_command, period);
    measured_integral.accumulate(measured.segment<3>(kXp), period);
    true_error_integral.accumulate(error, period);

    failure = hold_for_one_period(plant, applied, settings, workspace, x, t);
  }

  if (failure) {
    summary.status = controller_failed ? RunStatus::failed : RunStatus::diverged;
    summary.reason = *failure;
    summary.end_time = t;
  } else {
    summary.end_time = static_cast<double>(samples) * period;
  }
  metrics.finish(summary);
  summary.saturation = limiter.counts();
  summary.controller_counters = law.counters();
  return result;
}

}  // namespace thetad::sim
