#pragma once

#include <array>
#include <random>
#include <string_view>

#include <Eigen/Core>

#include "core/sim/dryden.hpp"

namespace thetad::sim {

// Continuous turbulence at the plant rate (docs/model.md §15.1-15.2): instead of the paper's white
// deviations held over each controller sample, a Dryden or a Gauss-Markov gust on top of the
// paper's mean wind. Off (`paper`) by default.
struct TurbulenceSettings {
  enum class Model {
    paper,         // the paper's deviations (WindGustSettings), nothing added: the default
    dryden,        // MIL-F-8785C / MIL-HDBK-1797 low altitude, by `intensity`, times `scale`
    gauss_markov,  // first order per NED axis: `sigma` (m/s) times `scale`, `correlation_time`
  };
  Model model = Model::paper;
  TurbulenceIntensity intensity = TurbulenceIntensity::light;
  double scale = 1.0;
  // Dryden: the airspeed its filters take is never below this (m/s), so that hover has a
  // turbulence (Taylor's frozen field needs a speed through it).
  double airspeed_floor = 1.0;
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();  // gauss_markov: north, east, down (m/s)
  double correlation_time = 1.0;                    // gauss_markov (s)

  // The names of the models and the intensities, in the order of their enums (files, factors).
  static constexpr std::array<std::string_view, 3> kModelNames = {"paper", "dryden", "gauss_markov"};
  static constexpr std::array<std::string_view, 3> kIntensityNames = {"light", "moderate", "severe"};

  bool active() const { return model != Model::paper; }
  // Throws thetad::Error naming the first setting out of range.
  void validate() const;
};

// Dryden components (u along the heading, v to its right, both horizontal; w down) in NED for
// heading ψ (rad).
Eigen::Vector3d heading_to_ned(const Eigen::Vector3d& uvw, double heading);

// One realization of TurbulenceSettings, advanced once per plant step from its own generator
// (RandomStream::turbulence). Allocates nothing after construction.
class Turbulence {
 public:
  explicit Turbulence(const TurbulenceSettings& settings);

  // The run's start: the generator seeded, the filters drawn from their stationary distribution.
  void start(std::uint64_t run_seed);
  // Advances by dt (s) at the helicopter's 18-state x in the wind `mean_wind_ned` (m/s): the
  // Dryden filters take the altitude -z_p and the airspeed |v_NED - mean wind| (floored).
  void step(double dt, const Eigen::VectorXd& x, const Eigen::Vector3d& mean_wind_ned);
  // The turbulence (m/s, NED) at the present state x; zero for `paper`.
  Eigen::Vector3d wind(const Eigen::VectorXd& x) const;

 private:
  TurbulenceSettings settings_;
  std::mt19937_64 rng_;
  DrydenFilters dryden_;
  Eigen::Vector3d markov_ = Eigen::Vector3d::Zero();  // unit-variance Gauss-Markov states
};

}  // namespace thetad::sim
