#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/helicopter/helicopter.hpp"
#include "core/sim/disturbances.hpp"
#include "core/sim/simulator.hpp"

namespace thetad::sim {

// The paper's disturbances of the helicopter (docs/model.md §8): Table 1's parameters drawn once per
// run, and per controller sample the gust, the wind-component and induced-velocity noise, the
// measurement noise, the actuator noise, then the servo limits; the rotor speed follows the
// applied thrust; DivergenceLimits end the run. Each switch of `settings` turns one off. Beyond the
// paper (§15, all off by default): turbulence and 1 - cosine gusts at the plant rate (advance()),
// additive sensor noise, and the servo chain delay, actuator noise, lag, rate and magnitude limits.
//
// The draws come from the run's generator in a fixed order: the Table 1 parameters in start(),
// then per sample the SampleDraws::kCount normals of SampleDraws::draw. All draws are taken whatever
// the switches say, so the same seed gives the same realization of every disturbance for every
// controller and every subset of disturbances. The later sources draw from their own streams
// (RandomStream), so that switching them on leaves these draws as they are.
class HelicopterDisturbances final : public Disturbances {
 public:
  HelicopterDisturbances(const SimulationSettings& settings,
                         const heli::Parameters& nominal = heli::Parameters::nominal(),
                         const heli::ModelOptions& options = heli::ModelOptions::resolved());

  const SdcPlant& start(std::mt19937_64& rng) override;
  void sample(double t, const Eigen::VectorXd& x, std::mt19937_64& rng) override;
  // The noisy 18-state (core/sim/noise.hpp, measure()): its integral entries hold the integral of
  // the measured position by the PositionIntegral rule.
  void measure(const Eigen::VectorXd& x, const Reference& reference, Eigen::Ref<Eigen::VectorXd> measured) override;
  std::optional<std::string> actuate(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& command,
                                     Eigen::VectorXd& applied) override;
  std::optional<std::string> check(const Eigen::VectorXd& x, double t) const override;
  void advance(double t, double dt, const Eigen::VectorXd& x) override;
  // sat_* (0 free, 1 held at a magnitude bound, 2 slowed by the rate limit), Omega_mr, wind_N/E/D.
  bool input_limited() const override { return limiter_.at_magnitude_bound(); }
  std::vector<LogColumn> log_columns() const override;
  void log_values(std::vector<double>& row) const override;
  void finish(RunSummary& summary) const override;

 private:
  // The plant's environment: the sample's with the turbulence and the gusts at (t, x) added.
  void set_moving_air(double t, const Eigen::VectorXd& x);

  SimulationSettings settings_;
  heli::Parameters nominal_;
  heli::ModelOptions options_;
  std::optional<heli::Helicopter> plant_;  // with this run's drawn parameters, from start()
  std::vector<std::pair<std::string, double>> parameter_factors_;
  NoiseLevels levels_;
  WindGust gust_;
  Turbulence turbulence_;
  SensorNoise sensor_noise_;
  TransportDelay delay_;
  ServoLag lag_;
  ActuatorLimiter limiter_;
  Eigen::VectorXd delayed_;                           // the command after the transport delay
  heli::Environment environment_;                     // the sample's, before turbulence and gusts
  bool moving_air_ = false;                           // turbulence or discrete gusts
  SampleDraws draws_;
  PositionIntegral measured_integral_;
  double rotor_speed_ = 0.0;
};

// The columns of every helicopter run's log, in order: what its CSV files are checked against.
const std::vector<LogColumn>& helicopter_log_schema();
// The index in helicopter_log_schema() of the column with this CSV header; throws thetad::Error
// when there is none.
Eigen::Index helicopter_log_column(const std::string& header);

// Flies `law` on the helicopter (nominal parameters and model options, drawn and disturbed by
// HelicopterDisturbances) from x0 (the 18-state, s = 1) for settings.duration.
RunResult simulate(ControlLaw& law, const ReferenceTrajectory& reference, const Eigen::VectorXd& x0,
                   const SimulationSettings& settings,
                   const heli::Parameters& nominal = heli::Parameters::nominal(),
                   const heli::ModelOptions& options = heli::ModelOptions::resolved(),
                   const std::function<void(double t)>& progress = {});

}  // namespace thetad::sim
