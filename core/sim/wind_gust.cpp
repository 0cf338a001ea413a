#include "core/sim/wind_gust.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace thetad::sim {

double mean_north_wind(double z_p) {
  constexpr double kMinAltitude = 0.1;  // m: 1.258 + 0.949 log10(h) is -inf at h = 0
  const double altitude = std::max(-z_p, kMinAltitude);
  return std::max(0.0, 1.258 + 0.949 * std::log10(altitude));
}

WindGust::WindGust(const WindGustSettings& settings, double sample_period) : settings_(settings) {
  if (!(sample_period > 0.0)) throw Error("WindGust: the sample period must be positive");
  if (!(settings.sigma >= 0.0)) throw Error("WindGust: sigma must be non-negative");
  if (!(settings.amplitude_scale >= 0.0) || !std::isfinite(settings.amplitude_scale))
    throw Error("WindGust: the amplitude scale must be finite and non-negative");
  if (!(settings.onset >= 0.0) || !std::isfinite(settings.onset))
    throw Error("WindGust: the onset must be a finite, non-negative time");
  if (settings.model == WindGustSettings::Model::gauss_markov) {
    if (!(settings.correlation_time > 0.0))
      throw Error("WindGust: the Gauss-Markov correlation time must be positive");
    decay_ = std::exp(-sample_period / settings.correlation_time);
    innovation_scale_ = settings.sigma * std::sqrt(1.0 - decay_ * decay_);
  }
}

Eigen::Vector3d WindGust::sample(double t, double z_p, const Eigen::Vector2d& standard_normal) {
  if (!settings_.enabled || t < settings_.onset) return Eigen::Vector3d::Zero();
  // The first sample is drawn from the stationary distribution in both models, so the gust is
  // statistically the same from t0 on.
  if (settings_.model == WindGustSettings::Model::held_white || !started_) {
    deviation_ = settings_.sigma * standard_normal;
  } else {
    deviation_ = decay_ * deviation_ + innovation_scale_ * standard_normal;
  }
  started_ = true;
  return settings_.amplitude_scale * Eigen::Vector3d(mean_north_wind(z_p) + deviation_.x(), deviation_.y(), 0.0);
}

}  // namespace thetad::sim
