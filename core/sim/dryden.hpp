#pragma once

#include <random>

#include <Eigen/Core>

namespace thetad::sim {

// Dryden turbulence of MIL-F-8785C §3.7 and MIL-HDBK-1797, its low-altitude form (docs/model.md
// §15.1). Everything here is in SI units; the standard's feet and knots are converted inside.

// The standard's three intensities, by the wind speed W20 at 20 ft: 15, 30 and 45 kt.
enum class TurbulenceIntensity { light, moderate, severe };
// W20 (m/s) of an intensity.
double wind_speed_at_20ft(TurbulenceIntensity intensity);

// The low-altitude formulas hold from kDrydenMinAltitude to kDrydenMaxAltitude: the altitude is
// clamped to that band (L_w = h vanishes at the ground; above 1000 ft the standard changes model).
inline constexpr double kDrydenMinAltitude = 3.048;  // m (10 ft)
inline constexpr double kDrydenMaxAltitude = 304.8;  // m (1000 ft)

// Intensities σ (m/s) and length scales L (m) of the components u (longitudinal), v (lateral),
// w (vertical) at altitude h (m, clamped), with h' = h in ft:
//   L_w = h', L_u = L_v = h' / (0.177 + 0.000823 h')^1.2,
//   σ_w = 0.1 W20, σ_u = σ_v = σ_w / (0.177 + 0.000823 h')^0.4.
struct DrydenScales {
  Eigen::Vector3d sigma;
  Eigen::Vector3d length;
};
DrydenScales dryden_scales(double altitude, TurbulenceIntensity intensity);

// The one-sided PSD ((m/s)^2/Hz, integrating to σ^2 over 0 ... ∞ Hz) of component `axis` (0 u,
// 1 v, 2 w) at frequency f (Hz) for airspeed V (m/s), with Ω = 2π f L / V:
//   u:    4 σ^2 (L/V) / (1 + Ω^2)
//   v, w: 2 σ^2 (L/V) (1 + 3 Ω^2) / (1 + Ω^2)^2
double dryden_psd(int axis, const DrydenScales& scales, double airspeed, double frequency);

// The shaping filters u: σ √(2L/πV) / (1 + L s/V), v and w: σ √(L/πV) (1 + √3 L s/V) / (1 + L s/V)^2
// (in the standard's ω-convention), driven by white noise, in time normalized by L/V so that their
// states have a stationary covariance independent of the airspeed and the length scale; each step
// is the exact discretization for its dt, so the sampled sequence has the continuous spectrum
// (up to aliasing) at any rate. Allocates nothing.
class DrydenFilters {
 public:
  // The states drawn from their stationary distribution: the turbulence is stationary from t0.
  void start(std::mt19937_64& rng);
  // Advances the states by dt (s) with the length scales of `scales` at airspeed V (m/s, > 0).
  void step(double dt, const DrydenScales& scales, double airspeed, std::mt19937_64& rng);
  // [u, v, w] (m/s) of the present states at the intensities of `scales`.
  Eigen::Vector3d value(const DrydenScales& scales) const;

 private:
  double longitudinal_ = 0.0;
  Eigen::Vector2d lateral_ = Eigen::Vector2d::Zero(), vertical_ = Eigen::Vector2d::Zero();
};

}  // namespace thetad::sim
