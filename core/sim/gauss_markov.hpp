#pragma once

#include <cmath>
#include <numbers>

namespace thetad::sim {

// A first-order Gauss-Markov process with unit variance, normalized in time: ξ' = -ξ/τ + √(2/τ) η
// with η unit white noise. One exact step of length dt from `state`, given h = dt/τ and a standard
// normal draw: the stationary variance stays 1 for any step, so the sampled sequence has the
// continuous spectrum (up to aliasing) whatever the rate it is advanced at (docs/model.md §15.2).
inline double gauss_markov_step(double state, double h, double standard_normal) {
  // 1 - e^{-2h} without cancellation at plant steps far below τ.
  return std::exp(-h) * state + std::sqrt(-std::expm1(-2.0 * h)) * standard_normal;
}

// The one-sided PSD ((unit)^2/Hz, integrating to σ^2 over 0 ... ∞ Hz) of σ ξ at frequency f (Hz)
// for correlation time τ (s): 4 σ^2 τ / (1 + (2π f τ)^2).
inline double gauss_markov_psd(double sigma, double correlation_time, double frequency) {
  const double wt = 2.0 * std::numbers::pi * frequency * correlation_time;
  return 4.0 * sigma * sigma * correlation_time / (1.0 + wt * wt);
}

}  // namespace thetad::sim
