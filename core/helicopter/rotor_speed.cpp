#include "core/helicopter/rotor_speed.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/error.hpp"

namespace thetad::heli {

namespace {

// A4 written as g(Omega) = k Omega sqrt(V_h^2 + (c Omega - w_a)^2) - T with k = 2 eta_w lambda0
// rho pi R^3 and c = lambda0 R; this struct evaluates g and g' (docs/model.md §4.2).
struct ThrustResidual {
  double k, c, vh2, w_a, thrust;

  double operator()(double omega) const {
    const double y = c * omega - w_a;
    return k * omega * std::sqrt(vh2 + y * y) - thrust;
  }
  // g and g' = k (V_h^2 + y^2 + Omega c y)/sqrt(V_h^2 + y^2) with one square root (a Newton step
  // needs both); g' is NaN at the kink V_h = 0, y = 0.
  struct Slope {
    double value, derivative;
  };
  Slope with_derivative(double omega) const {
    const double y = c * omega - w_a;
    const double norm = std::sqrt(vh2 + y * y);
    return {k * omega * norm - thrust, k * (vh2 + y * y + omega * c * y) / norm};
  }
};

ThrustResidual residual(const Parameters& p, double thrust, double horizontal_airspeed, double w_a) {
  const double r = p.radius_mr;
  return {2.0 * p.eta_w * p.lambda0 * p.rho * std::numbers::pi * r * r * r, p.lambda0 * r,
          horizontal_airspeed * horizontal_airspeed, w_a, thrust};
}

// The root of a g that is monotonic on [lo, hi] with g(lo), g(hi) of opposite signs (or zero):
// Newton steps kept inside the shrinking bracket, bisection whenever a step would leave it.
double root_in_monotonic_interval(const ThrustResidual& g, double lo, double hi, double g_lo, double start) {
  constexpr double kRelativeTolerance = 1e-12;
  double omega = start;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const auto [value, derivative] = g.with_derivative(omega);
    if (value == 0.0) return omega;
    if ((value < 0.0) == (g_lo < 0.0)) {
      lo = omega;
      g_lo = value;
    } else {
      hi = omega;
    }
    double next = omega - value / derivative;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // also catches a NaN step at the kink
    const bool converged = std::abs(next - omega) <= kRelativeTolerance * next || hi - lo <= kRelativeTolerance * lo;
    omega = next;
    if (converged) return omega;
  }
  return omega;  // 200 safeguarded steps halve the bracket at least ~100 times: below any tolerance
}

}  // namespace

double main_rotor_thrust(const Parameters& p, double rotor_speed, double horizontal_airspeed, double w_a) {
  return residual(p, 0.0, horizontal_airspeed, w_a)(rotor_speed);
}

double main_rotor_speed(const Parameters& p, double thrust, double horizontal_airspeed, double w_a, double hint) {
  if (!std::isfinite(thrust) || thrust < 0.0 || !std::isfinite(horizontal_airspeed) || !std::isfinite(w_a)) {
    std::ostringstream message;
    message << "main-rotor speed (A4): thrust T_mr = " << thrust << " N with V_h = " << horizontal_airspeed
            << " m/s, w_a = " << w_a << " m/s is not a finite non-negative thrust at a finite airspeed";
    throw Error(message.str());
  }
  const ThrustResidual g = residual(p, thrust, horizontal_airspeed, w_a);

  // Break [Omega_min, Omega_max] at the zeros of g' (Omega = (3 w_a -/+ sqrt(w_a^2 - 8 V_h^2))/(4c),
  // which exist only for w_a > 0, w_a^2 > 8 V_h^2): g is monotonic between the breaks.
  std::array<double, 4> breaks{kMinRotorSpeed, kMaxRotorSpeed, kMaxRotorSpeed, kMaxRotorSpeed};
  int count = 2;
  const double discriminant = w_a * w_a - 8.0 * g.vh2;
  if (w_a > 0.0 && discriminant > 0.0) {
    const double root = std::sqrt(discriminant);
    for (const double critical : {(3.0 * w_a - root) / (4.0 * g.c), (3.0 * w_a + root) / (4.0 * g.c)}) {
      if (critical > breaks[count - 2] && critical < kMaxRotorSpeed) {
        breaks[count - 1] = critical;
        breaks[count++] = kMaxRotorSpeed;
      }
    }
  }

  double best = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i + 1 < count; ++i) {
    const double lo = breaks[i], hi = breaks[i + 1];
    const double g_lo = g(lo), g_hi = g(hi);
    if ((g_lo > 0.0 && g_hi > 0.0) || (g_lo < 0.0 && g_hi < 0.0)) continue;
    const double start = std::clamp(hint, lo, hi);
    const double omega = g_lo == 0.0 ? lo : g_hi == 0.0 ? hi : root_in_monotonic_interval(g, lo, hi, g_lo, start);
    if (std::isnan(best) || std::abs(omega - hint) < std::abs(best - hint)) best = omega;
  }
  if (std::isnan(best)) {
    std::ostringstream message;
    message << "main-rotor speed (A4): no root for thrust T_mr = " << thrust << " N in the bracket ["
            << kMinRotorSpeed << ", " << kMaxRotorSpeed << "] rad/s (V_h = " << horizontal_airspeed
            << " m/s, w_a = " << w_a << " m/s; A4 gives " << main_rotor_thrust(p, kMinRotorSpeed, horizontal_airspeed, w_a)
            << " N at " << kMinRotorSpeed << " rad/s and " << main_rotor_thrust(p, kMaxRotorSpeed, horizontal_airspeed, w_a)
            << " N at " << kMaxRotorSpeed << " rad/s)";
    throw Error(message.str());
  }
  return best;
}

Dual implicit_rotor_speed(const Parameters& p, double rotor_speed, const Dual& thrust,
                          const Dual& horizontal_airspeed_squared, const Dual& w_a) {
  ThrustResidual g = residual(p, thrust.value(), 0.0, w_a.value());
  g.vh2 = horizontal_airspeed_squared.value();
  const double y = g.c * rotor_speed - g.w_a, norm = std::sqrt(g.vh2 + y * y);
  const double per_airspeed_squared = g.k * rotor_speed / (2.0 * norm), per_w_a = -g.k * rotor_speed * y / norm;
  return Dual(rotor_speed, (thrust.derivatives() - per_airspeed_squared * horizontal_airspeed_squared.derivatives() -
                            per_w_a * w_a.derivatives()) /
                               g.with_derivative(rotor_speed).derivative);
}

}  // namespace thetad::heli
