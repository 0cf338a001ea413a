#include "core/sim/dryden.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "core/sim/gauss_markov.hpp"
#include "core/sim/noise.hpp"

namespace thetad::sim {

namespace {

constexpr double kFoot = 0.3048;      // m
constexpr double kKnot = 1852.0 / 3600.0;  // m/s

// The v and w filters in normalized time s' = s L/V, driven by √2 η' (η' unit white noise):
//   ξ2' = -ξ2 + √2 η',  ξ1' = -ξ1 + ξ2,  y = σ (c1 ξ1 + c2 ξ2),
// which is σ √2 (c1 + c2 (1 + s')) / (1 + s')^2: (1 + √3 s') / (1 + s')^2 up to the gain when
// c2 = √3 (c1 + c2), and a unit variance of y/σ when c2 = √(3/2). The stationary covariance of
// (ξ1, ξ2) is [[1/2, 1/2], [1/2, 1]] whatever L and V.
const double kC2 = std::sqrt(1.5);
const double kC1 = kC2 * (1.0 / std::sqrt(3.0) - 1.0);

// ∫_0^h τ^n e^{-2τ} dτ for n = 0, 1, 2: by its series where h is small (the closed forms cancel
// catastrophically at plant steps of 1e-6 L/V), by the closed forms elsewhere.
std::array<double, 3> exponential_moments(double h) {
  std::array<double, 3> moments{};
  if (h < 0.25) {
    // Terms (-2h)^k h^(n+1) / (k! (n + k + 1)), alternating and falling at 2h < 1/2: summed until
    // the next is below the last bit (at plant steps, h ~ 1e-4: four terms).
    double power = h;  // h^(n+1)
    for (std::size_t n = 0; n < 3; ++n, power *= h) {
      double term = power, sum = 0.0;
      for (int k = 0; k < 24 && std::abs(term) > 1e-17 * std::abs(sum); ++k) {
        sum += term / static_cast<double>(static_cast<int>(n) + k + 1);
        term *= -2.0 * h / (k + 1);
      }
      moments[n] = sum;
    }
    return moments;
  }
  const double e = std::exp(-2.0 * h);
  moments[0] = -std::expm1(-2.0 * h) / 2.0;
  moments[1] = (1.0 - e * (1.0 + 2.0 * h)) / 4.0;
  moments[2] = (2.0 - e * (2.0 + 4.0 * h + 4.0 * h * h)) / 8.0;
  return moments;
}

// One exact step of the (ξ1, ξ2) pair over normalized time h, with two standard normals:
// Φ = e^{-h} [[1, h], [0, 1]], and the innovation's covariance 2 ∫_0^h e^{-2τ} [[τ², τ], [τ, 1]] dτ
// by its Cholesky factor.
Eigen::Vector2d second_order_step(const Eigen::Vector2d& state, double h, const Eigen::Vector2d& normal) {
  const std::array<double, 3> m = exponential_moments(h);
  const double q11 = 2.0 * m[2], q12 = 2.0 * m[1], q22 = 2.0 * m[0];
  const double l11 = std::sqrt(q11), l21 = q12 / l11, l22 = std::sqrt(std::max(0.0, q22 - l21 * l21));
  const double decay = std::exp(-h);
  return {decay * (state.x() + h * state.y()) + l11 * normal.x(),
          decay * state.y() + l21 * normal.x() + l22 * normal.y()};
}

// A draw of (ξ1, ξ2) from the stationary covariance [[1/2, 1/2], [1/2, 1]].
Eigen::Vector2d stationary_pair(const Eigen::Vector2d& normal) {
  const double r = std::sqrt(0.5);
  return {r * normal.x(), r * normal.x() + r * normal.y()};
}

}  // namespace

double wind_speed_at_20ft(TurbulenceIntensity intensity) {
  switch (intensity) {
    case TurbulenceIntensity::light: return 15.0 * kKnot;
    case TurbulenceIntensity::moderate: return 30.0 * kKnot;
    case TurbulenceIntensity::severe: break;
  }
  return 45.0 * kKnot;
}

DrydenScales dryden_scales(double altitude, TurbulenceIntensity intensity) {
  const double feet = std::clamp(altitude, kDrydenMinAltitude, kDrydenMaxAltitude) / kFoot;
  const double base = 0.177 + 0.000823 * feet;
  const double horizontal_length = feet / std::pow(base, 1.2) * kFoot;
  const double sigma_w = 0.1 * wind_speed_at_20ft(intensity);
  const double sigma_horizontal = sigma_w / std::pow(base, 0.4);
  return {{sigma_horizontal, sigma_horizontal, sigma_w}, {horizontal_length, horizontal_length, feet * kFoot}};
}

double dryden_psd(int axis, const DrydenScales& scales, double airspeed, double frequency) {
  const double sigma = scales.sigma[axis], time = scales.length[axis] / airspeed;
  const double omega = 2.0 * std::numbers::pi * frequency * time, omega2 = omega * omega;
  if (axis == 0) return gauss_markov_psd(sigma, time, frequency);
  return 2.0 * sigma * sigma * time * (1.0 + 3.0 * omega2) / ((1.0 + omega2) * (1.0 + omega2));
}

void DrydenFilters::start(std::mt19937_64& rng) {
  const Eigen::Vector2d first = standard_normal_pair(rng), second = standard_normal_pair(rng),
                        third = standard_normal_pair(rng);
  longitudinal_ = first.x();
  lateral_ = stationary_pair({first.y(), second.x()});
  vertical_ = stationary_pair({second.y(), third.x()});
}

void DrydenFilters::step(double dt, const DrydenScales& scales, double airspeed, std::mt19937_64& rng) {
  const Eigen::Vector2d first = standard_normal_pair(rng), second = standard_normal_pair(rng),
                        third = standard_normal_pair(rng);
  const Eigen::Vector3d h = dt * airspeed * scales.length.cwiseInverse();
  longitudinal_ = gauss_markov_step(longitudinal_, h.x(), first.x());
  lateral_ = second_order_step(lateral_, h.y(), {first.y(), second.x()});
  vertical_ = second_order_step(vertical_, h.z(), {second.y(), third.x()});
}

Eigen::Vector3d DrydenFilters::value(const DrydenScales& scales) const {
  return {scales.sigma.x() * longitudinal_, scales.sigma.y() * (kC1 * lateral_.x() + kC2 * lateral_.y()),
          scales.sigma.z() * (kC1 * vertical_.x() + kC2 * vertical_.y())};
}

}  // namespace thetad::sim
