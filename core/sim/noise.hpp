#pragma once

#include <random>

#include <Eigen/Core>

#include "core/helicopter/helicopter.hpp"

namespace thetad::sim {

// A standard normal draw from the run's generator by the Box-Muller transform on 53-bit uniforms.
// Written out rather than std::normal_distribution, whose algorithm (and its cached second value)
// differs between standard libraries: the same seed must give the same run everywhere.
// Returns a pair of independent N(0, 1) values.
Eigen::Vector2d standard_normal_pair(std::mt19937_64& rng);

// All the standard normal draws of one controller sample, in the fixed order in which draw() takes
// them from the generator: the members in declaration order, each vector entry by entry. Every
// draw is taken whether or not its disturbance is switched on, so that switching one disturbance
// off (or changing the controller) leaves the realization of all the others unchanged.
struct SampleDraws {
  static constexpr int kCount = 26;
  Eigen::Matrix<double, 14, 1> measurement;  // V_track entries 1-14 (x_p - x_c ... b1)
  Eigen::Matrix<double, 5, 1> actuator;      // T_mr, delta_ped, delta_col, delta_lon, delta_lat
  Eigen::Vector2d gust;                      // north, east
  Eigen::Vector3d wind_body;                 // u_w, v_w, w_w (Table 1 #26-28)
  double induced_main = 0.0;                 // V_imr (#29)
  double induced_tail = 0.0;                 // V_itr (#30)

  void draw(std::mt19937_64& rng);
};

// Relative standard deviations (fractions, 0.05 for 5 %) of the noise channels.
struct NoiseLevels {
  Eigen::Matrix<double, 14, 1> measurement;  // in V_track order: x_p, y_p, z_p, u ... b1
  Eigen::Matrix<double, 5, 1> actuator;      // in input order
  Eigen::Vector3d wind_body;                 // u_w, v_w, w_w
  double induced_main = 0.0;
  double induced_tail = 0.0;

  // The percents of Table 1 as core/helicopter/uncertainty.hpp exports them, times `scale`.
  static NoiseLevels from_uncertainty_table(double scale = 1.0);
};

// What the 5 % measurement noise multiplies (docs/model.md §9.3, §11 ).
enum class MeasurementNoiseOn {
  feedback_signal,  // the V_track entries: position errors x_p - x_c, the other 11 states as they are
  absolute_state,   // the literal reading: the absolute positions (diverges with the paper's Q)
};

struct NoiseSettings {
  bool measurement = true;
  MeasurementNoiseOn measurement_on = MeasurementNoiseOn::feedback_signal;
  bool actuator = true;
  bool wind_component = true;     // Table 1 #26-28
  bool induced_velocity = true;   // Table 1 #29-30
  // Multiplies every noise level of Table 1 (campaign sweeps): 0 silences them, 2 doubles them.
  double scale = 1.0;
};

// The measured 18-state the controller sees. Entries 0-13 carry multiplicative noise
// y = s (1 + level n) (zero signal, zero noise): with feedback_signal the positions are built as
// x_c + (x_p - x_c)(1 + level n), so that measured position minus reference is the true error
// times (1 + level n). Entries 14-16 are not sensed: they hold the integral of the measured
// position by the PositionIntegral rule (passed in), so measured x_i minus the reference integral
// is the integral error of V_track. Entry 17 is the controller's bias state, s = 1 (docs/model.md §2).
void measure(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Vector3d& reference_position,
             const Eigen::Vector3d& measured_position_integral, const SampleDraws& draws,
             const NoiseLevels& levels, const NoiseSettings& settings, Eigen::Ref<Eigen::VectorXd> measured);

// u_applied = u_command (1 + level n) per channel (docs/model.md §9.4), or the command when switched off.
void apply_actuator_noise(const Eigen::Ref<const Eigen::VectorXd>& command, const SampleDraws& draws,
                          const NoiseLevels& levels, const NoiseSettings& settings,
                          Eigen::Ref<Eigen::VectorXd> applied);

// The plant's environment for one sample: the gust wind, the body-frame wind-component noise
// (#26-28) and the induced-velocity noise (#29-30) as multiplicative scales.
heli::Environment sample_environment(const Eigen::Vector3d& wind_ned, const SampleDraws& draws,
                                     const NoiseLevels& levels, const NoiseSettings& settings);

}  // namespace thetad::sim
