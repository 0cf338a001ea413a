#include "core/sim/turbulence.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "core/sim/gauss_markov.hpp"
#include "core/sim/noise.hpp"
#include "core/sim/seed.hpp"

namespace thetad::sim {

namespace {

// v_NED = R(φ, θ, ψ) (u, v, w), Eq. (1)-(2).
Eigen::Vector3d ground_velocity(const Eigen::VectorXd& x) {
  using namespace heli;
  const double sf = std::sin(x[kPhi]), cf = std::cos(x[kPhi]), st = std::sin(x[kTheta]), ct = std::cos(x[kTheta]),
               sp = std::sin(x[kPsi]), cp = std::cos(x[kPsi]);
  Eigen::Matrix3d rotation;
  rotation << ct * cp, sf * st * cp - cf * sp, cf * st * cp + sf * sp,  //
      ct * sp, sf * st * sp + cf * cp, cf * st * sp - sf * cp,          //
      -st, sf * ct, cf * ct;
  return rotation * x.segment<3>(kU);
}

}  // namespace

void TurbulenceSettings::validate() const {
  if (!(scale >= 0.0) || !std::isfinite(scale)) throw Error("turbulence: the scale must be finite and >= 0");
  if (!(airspeed_floor > 0.0) || !std::isfinite(airspeed_floor))
    throw Error("turbulence: the airspeed floor must be positive and finite");
  if (!sigma.allFinite() || (sigma.array() < 0.0).any())
    throw Error("turbulence: every Gauss-Markov sigma must be finite and >= 0");
  if (!(correlation_time > 0.0) || !std::isfinite(correlation_time))
    throw Error("turbulence: the Gauss-Markov correlation time must be positive and finite");
}

Eigen::Vector3d heading_to_ned(const Eigen::Vector3d& uvw, double heading) {
  const double c = std::cos(heading), s = std::sin(heading);
  return {c * uvw.x() - s * uvw.y(), s * uvw.x() + c * uvw.y(), uvw.z()};
}

Turbulence::Turbulence(const TurbulenceSettings& settings) : settings_(settings) { settings_.validate(); }

void Turbulence::start(std::uint64_t run_seed) {
  rng_.seed(stream_seed(run_seed, RandomStream::turbulence));
  if (settings_.model == TurbulenceSettings::Model::dryden) dryden_.start(rng_);
  if (settings_.model == TurbulenceSettings::Model::gauss_markov) {
    const Eigen::Vector2d first = standard_normal_pair(rng_), second = standard_normal_pair(rng_);
    markov_ = {first.x(), first.y(), second.x()};
  }
}

void Turbulence::step(double dt, const Eigen::VectorXd& x, const Eigen::Vector3d& mean_wind_ned) {
  if (settings_.model == TurbulenceSettings::Model::dryden) {
    const double airspeed = std::max(settings_.airspeed_floor, (ground_velocity(x) - mean_wind_ned).norm());
    dryden_.step(dt, dryden_scales(-x[heli::kZp], settings_.intensity), airspeed, rng_);
  } else if (settings_.model == TurbulenceSettings::Model::gauss_markov) {
    const Eigen::Vector2d first = standard_normal_pair(rng_), second = standard_normal_pair(rng_);
    const double h = dt / settings_.correlation_time;
    markov_ = {gauss_markov_step(markov_.x(), h, first.x()), gauss_markov_step(markov_.y(), h, first.y()),
               gauss_markov_step(markov_.z(), h, second.x())};
  }
}

Eigen::Vector3d Turbulence::wind(const Eigen::VectorXd& x) const {
  switch (settings_.model) {
    case TurbulenceSettings::Model::dryden:
      return settings_.scale *
             heading_to_ned(dryden_.value(dryden_scales(-x[heli::kZp], settings_.intensity)), x[heli::kPsi]);
    case TurbulenceSettings::Model::gauss_markov:
      return settings_.scale * settings_.sigma.cwiseProduct(markov_);
    case TurbulenceSettings::Model::paper: break;
  }
  return Eigen::Vector3d::Zero();
}

}  // namespace thetad::sim
