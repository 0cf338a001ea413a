#pragma once

// What the helicopter's tests share: fixed-size names for its vectors and matrices, the nominal
// parameters, the state at rest on the ground, the model option sets and random states, inputs
// and environments of the test envelope.
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/helicopter/helicopter.hpp"

namespace thetad::heli::testing {

using Vector18 = Eigen::Matrix<double, kStateDim, 1>;
using Vector5 = Eigen::Matrix<double, kInputDim, 1>;
using Matrix18 = Eigen::Matrix<double, kStateDim, kStateDim>;
using Matrix18x5 = Eigen::Matrix<double, kStateDim, kInputDim>;

inline const Parameters kNominal = Parameters::nominal();

// Level, at rest on the ground, s = 1.
inline Eigen::VectorXd rest_state() {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kStateDim);
  x[kS] = 1.0;
  return x;
}

struct NamedOptions {
  std::string name;
  ModelOptions options;
};

inline std::vector<NamedOptions> option_sets() {
  ModelOptions governor = ModelOptions::resolved();
  governor.rotor_speed_model = ModelOptions::RotorSpeedModel::governor;
  ModelOptions paper_governor = ModelOptions::paper();
  paper_governor.rotor_speed_model = ModelOptions::RotorSpeedModel::governor;
  ModelOptions alternatives = ModelOptions::resolved();  // the remaining switch values
  alternatives.yaw_inertia = ModelOptions::YawInertia::plus_rotor;
  alternatives.tail_rotor_torque = ModelOptions::TailRotorTorque::none;
  alternatives.induced_velocity_model = ModelOptions::InducedVelocityModel::lambda0_omega_r;
  ModelOptions izz = ModelOptions::paper();
  izz.yaw_inertia = ModelOptions::YawInertia::izz;
  return {{"resolved", ModelOptions::resolved()}, {"paper", ModelOptions::paper()}, {"resolved+governor", governor},
          {"paper+governor", paper_governor}, {"alternatives", alternatives}, {"paper+izz", izz}};
}

inline double uniform(std::mt19937_64& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

// A random state of the test envelope: speed up to 20 m/s, angles to +/-60 deg, rates to 3 rad/s,
// flapping to 0.2 rad, s in [0.5, 2].
inline Eigen::VectorXd random_state(std::mt19937_64& rng) {
  Eigen::VectorXd x(kStateDim);
  for (int i = kXp; i <= kZp; ++i) x[i] = uniform(rng, -50, 50);
  Eigen::Vector3d direction(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
  x.segment<3>(kU) = direction.normalized() * uniform(rng, 0, 20);
  const double sixty = std::numbers::pi / 3;
  x[kPhi] = uniform(rng, -sixty, sixty);
  x[kTheta] = uniform(rng, -sixty, sixty);
  x[kPsi] = uniform(rng, -std::numbers::pi, std::numbers::pi);
  for (int i = kP; i <= kR; ++i) x[i] = uniform(rng, -3, 3);
  x[kA1] = uniform(rng, -0.2, 0.2);
  x[kB1] = uniform(rng, -0.2, 0.2);
  for (int i = kXi; i <= kZi; ++i) x[i] = uniform(rng, -100, 100);
  x[kS] = uniform(rng, 0.5, 2.0);
  return x;
}

// Inputs around hover (thrust high enough that A4 has a root at every state of the envelope).
inline Eigen::VectorXd random_input(std::mt19937_64& rng) {
  Eigen::VectorXd u(kInputDim);
  u << uniform(rng, 60, 120), uniform(rng, -0.4, 0.1), uniform(rng, -0.1, 0.1), uniform(rng, -0.05, 0.05),
      uniform(rng, -0.05, 0.05);
  return u;
}

inline Environment random_environment(std::mt19937_64& rng) {
  Environment env;
  env.wind_ned = Eigen::Vector3d(uniform(rng, -3, 3), uniform(rng, -3, 3), uniform(rng, -1, 1));
  env.wind_body_scale = Eigen::Vector3d(uniform(rng, 0.9, 1.1), uniform(rng, 0.9, 1.1), uniform(rng, 0.9, 1.1));
  env.induced_main_scale = uniform(rng, 0.8, 1.2);
  env.induced_tail_scale = uniform(rng, 0.8, 1.2);
  return env;
}

}  // namespace thetad::heli::testing
