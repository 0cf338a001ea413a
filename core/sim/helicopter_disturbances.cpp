#include "core/sim/helicopter_disturbances.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "core/helicopter/uncertainty.hpp"
#include "core/sim/discrete_gust.hpp"

namespace thetad::sim {

namespace {

using heli::kInputDim;

std::string format_reason(const char* what, double value, double limit, const char* unit, double t) {
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "%s = %.6g %s exceeds %.6g %s at t = %.4f s", what, value, unit,
                limit, unit, t);
  return buffer;
}

// The paper's gust; with a turbulence model chosen, its mean wind alone (the turbulence replaces
// its held white deviations; their draws are still taken, so the other draws stay as they are).
WindGustSettings paper_gust(const SimulationSettings& settings) {
  WindGustSettings gust = settings.wind_gust;
  if (settings.turbulence.active()) gust.sigma = 0.0;
  return gust;
}

}  // namespace

HelicopterDisturbances::HelicopterDisturbances(const SimulationSettings& settings, const heli::Parameters& nominal,
                                               const heli::ModelOptions& options)
    : settings_(settings),
      nominal_(nominal),
      options_(options),
      levels_(NoiseLevels::from_uncertainty_table(settings.noise.scale)),
      gust_(paper_gust(settings), settings.controller_period()),
      turbulence_(settings.turbulence),
      sensor_noise_(settings.sensor_noise, settings.controller_period()),
      delay_(kInputDim, settings.servos.delay_samples),
      lag_(settings.servos.time_constant, settings.controller_period()),
      limiter_(settings.actuator_limits, settings.controller_period()),
      delayed_(kInputDim),
      moving_air_(settings.turbulence.active() || !settings.discrete_gusts.empty()) {}

const SdcPlant& HelicopterDisturbances::start(std::mt19937_64& rng) {
  // Drawn whether or not the uncertainty is on, so that every later draw is the same either way.
  heli::PerturbedParameters drawn = heli::perturbed_parameters(nominal_, rng, settings_.uncertainty_scale);
  if (!settings_.parameter_deviations.empty())
    drawn = heli::perturbed_parameters(nominal_, heli::parameter_draw(settings_.parameter_deviations),
                                       settings_.uncertainty_scale);
  plant_.emplace(settings_.parameter_uncertainty ? drawn.parameters : nominal_, options_);
  parameter_factors_.clear();
  if (settings_.parameter_uncertainty) {
    for (const auto& entry : drawn.report) {
      if (entry.category == heli::UncertaintyCategory::parameter) parameter_factors_.emplace_back(entry.name, entry.factor);
    }
  }
  gust_.reset();
  turbulence_.start(settings_.seed);
  sensor_noise_.start(settings_.seed);
  delay_.reset();
  lag_.reset();
  limiter_.reset();
  measured_integral_ = {};
  return *plant_;
}

void HelicopterDisturbances::sample(double t, const Eigen::VectorXd& x, std::mt19937_64& rng) {
  draws_.draw(rng);
  const Eigen::Vector3d wind = gust_.sample(t, x[heli::kZp], draws_.gust);
  environment_ = sample_environment(wind, draws_, levels_, settings_.noise);
  if (moving_air_) {
    set_moving_air(t, x);
  } else {
    plant_->set_environment(environment_);
  }
}

void HelicopterDisturbances::advance(double t, double dt, const Eigen::VectorXd& x) {
  if (!moving_air_) return;
  turbulence_.step(dt, x, environment_.wind_ned);
  set_moving_air(t, x);
}

void HelicopterDisturbances::set_moving_air(double t, const Eigen::VectorXd& x) {
  heli::Environment moved = environment_;
  moved.wind_ned += turbulence_.wind(x) + discrete_gust_wind(settings_.discrete_gusts, t);
  plant_->set_environment(moved);
}

void HelicopterDisturbances::measure(const Eigen::VectorXd& x, const Reference& reference,
                                     Eigen::Ref<Eigen::VectorXd> measured) {
  sim::measure(x, reference.position, measured_integral_.value, draws_, levels_, settings_.noise, measured);
  if (settings_.sensor_noise.active()) sensor_noise_.add(measured.head<heli::kPhysicalStateDim>());
  measured_integral_.accumulate(measured.segment<3>(heli::kXp), settings_.controller_period());
}

std::optional<std::string> HelicopterDisturbances::actuate(double t, const Eigen::VectorXd& x,
                                                           const Eigen::VectorXd& command, Eigen::VectorXd& applied) {
  // The servo chain of docs/model.md §15.5: delay, actuator noise, lag, rate and magnitude limits.
  if (settings_.servos.delay_samples > 0) {
    delayed_ = command;
    delay_.apply(delayed_);
    apply_actuator_noise(delayed_, draws_, levels_, settings_.noise, applied);
  } else {
    apply_actuator_noise(command, draws_, levels_, settings_.noise, applied);
  }
  if (settings_.servos.lagged()) lag_.apply(applied);
  limiter_.apply(applied);
  try {
    rotor_speed_ = plant_->rotor_speed(x, applied[heli::kTmr]);
  } catch (const Error& error) {
    return failure_reason("plant rotor speed", error, t);
  }
  return std::nullopt;
}

std::optional<std::string> HelicopterDisturbances::check(const Eigen::VectorXd& x, double t) const {
  using namespace heli;
  const DivergenceLimits& limits = settings_.limits;
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

std::vector<LogColumn> HelicopterDisturbances::log_columns() const {
  std::vector<LogColumn> columns;
  for (const auto& input : heli::Helicopter().input_columns()) columns.push_back({"sat_" + input.name, "flag"});
  columns.push_back({"Omega_mr", "rad_per_s"});
  columns.push_back({"wind_N", "m_per_s"});
  columns.push_back({"wind_E", "m_per_s"});
  columns.push_back({"wind_D", "m_per_s"});
  return columns;
}

void HelicopterDisturbances::log_values(std::vector<double>& row) const {
  const unsigned flags = limiter_.last_flags();
  for (int k = 0; k < kInputDim; ++k) {
    const bool magnitude = (flags >> k) & 1u, rate = (flags >> (k + kInputDim)) & 1u;
    row.push_back(magnitude ? 1.0 : rate ? 2.0 : 0.0);
  }
  row.push_back(rotor_speed_);
  const Eigen::Vector3d& wind = plant_->environment().wind_ned;
  row.insert(row.end(), wind.begin(), wind.end());
}

void HelicopterDisturbances::finish(RunSummary& summary) const {
  summary.model_options = options_.to_string();
  summary.parameter_factors = parameter_factors_;
  summary.saturation = limiter_.counts();
}

const std::vector<LogColumn>& helicopter_log_schema() {
  static const std::vector<LogColumn> schema = [] {
    const heli::Helicopter plant;
    return log_schema(plant, HelicopterDisturbances(SimulationSettings::ideal()));
  }();
  return schema;
}

Eigen::Index helicopter_log_column(const std::string& header) {
  const auto& schema = helicopter_log_schema();
  const auto found = std::find_if(schema.begin(), schema.end(), [&](const LogColumn& c) { return c.header() == header; });
  if (found == schema.end()) throw Error("the helicopter's run log has no column " + header);
  return static_cast<Eigen::Index>(found - schema.begin());
}

RunResult simulate(ControlLaw& law, const ReferenceTrajectory& reference, const Eigen::VectorXd& x0,
                   const SimulationSettings& settings, const heli::Parameters& nominal,
                   const heli::ModelOptions& options, const std::function<void(double t)>& progress) {
  settings.validate();
  if (x0.size() != heli::kStateDim)
    throw Error("simulate: x0 has " + std::to_string(x0.size()) + " entries, the helicopter has " +
                std::to_string(heli::kStateDim));
  HelicopterDisturbances disturbances(settings, nominal, options);
  return simulate(law, disturbances, reference, x0, settings, progress);
}

}  // namespace thetad::sim
