#pragma once

#include <Eigen/Core>

namespace thetad::sim {

// The gust of docs/model.md §9.2 (paper Sec. 2.4, scaled down from AC120-28D; A-4).
struct WindGustSettings {
  enum class Model {
    held_white,    // independent samples, zero-order held between controller samples (the default)
    gauss_markov,  // first-order Gauss-Markov deviations with the same stationary sigma
  };
  bool enabled = true;
  Model model = Model::held_white;
  double sigma = 0.199;            // m/s, north and east deviations
  double correlation_time = 1.0;   // s, gauss_markov only
  // Campaign sweeps: the whole wind (mean and deviations) times amplitude_scale (0: calm air, 1: the
  // paper's gust, 2: twice as strong), blowing from `onset` (s) on; calm air before it.
  double amplitude_scale = 1.0;
  double onset = 0.0;
};

// Mean north wind at the helicopter's position: max(0, 1.258 + 0.949 log10(h)) with the altitude
// h = max(-z_p, 0.1 m); the floor keeps the log finite at and below the ground (§4.3).
double mean_north_wind(double z_p);

// One gust realization. sample() is called once per controller sample with that sample's two
// standard normal draws (north, east) and returns the inertial wind [W_N, W_E, W_D], W_D = 0.
// The caller draws the normals so that the run's draw order stays in one place (the simulator).
class WindGust {
 public:
  WindGust(const WindGustSettings& settings, double sample_period);

  // Back to the state before the first sample.
  void reset() { started_ = false; }
  // The wind at time t (calm before the onset; the deviations start there).
  Eigen::Vector3d sample(double t, double z_p, const Eigen::Vector2d& standard_normal);

 private:
  WindGustSettings settings_;
  double decay_ = 0.0;             // exp(-T_c / tau): one-sample correlation of the deviations
  double innovation_scale_ = 0.0;  // sigma sqrt(1 - decay^2): keeps the stationary sigma
  Eigen::Vector2d deviation_ = Eigen::Vector2d::Zero();
  bool started_ = false;
};

}  // namespace thetad::sim
