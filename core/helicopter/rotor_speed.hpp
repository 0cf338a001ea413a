#pragma once

#include "core/helicopter/dual.hpp"
#include "core/helicopter/parameters.hpp"

namespace thetad::heli {

// The bracket in which the main-rotor speed is searched (docs/model.md §4.2, rad/s).
inline constexpr double kMinRotorSpeed = 20.0;
inline constexpr double kMaxRotorSpeed = 600.0;

// Main-rotor thrust of Eq. A4 at rotor speed Omega (rad/s), for the air-relative velocity of the
// hub: horizontal_airspeed = V_h = sqrt(u_a^2 + v_a^2), w_a the body-z component (down positive):
//   T = 2 eta_w lambda0 rho pi R^3 Omega sqrt(V_h^2 + (lambda0 R Omega - w_a)^2)
// (A4 with A5, A6 multiplied out for Omega > 0).
double main_rotor_thrust(const Parameters& p, double rotor_speed, double horizontal_airspeed, double w_a);

// Omega_mr solving A4 for the thrust T_mr (docs/model.md §4.2): the root in [kMinRotorSpeed,
// kMaxRotorSpeed], to 1e-12 relative, by safeguarded Newton with bisection fallback on each
// interval where A4 is monotonic. In fast descent relative to the air (w_a > 0 and
// w_a^2 > 8 V_h^2) A4 may have up to three roots; the one nearest `hint` is returned.
// Throws thetad::Error for a negative or non-finite thrust and when no root lies in the bracket
// (the message names the thrust, the airspeed and the bracket). Allocates nothing on success.
double main_rotor_speed(const Parameters& p, double thrust, double horizontal_airspeed, double w_a, double hint);

// `rotor_speed`, a root of A4 for thrust.value() (main_rotor_speed), with the derivatives the
// implicit-function theorem gives it through g(Omega; T, V_h^2, w_a) = 0, not those of the root
// finder's iteration: dOmega = (dT - dg/dV_h^2 dV_h^2 - dg/dw_a dw_a) / g'(Omega). V_h enters
// squared, so the derivative exists in hover too.
Dual implicit_rotor_speed(const Parameters& p, double rotor_speed, const Dual& thrust,
                          const Dual& horizontal_airspeed_squared, const Dual& w_a);

}  // namespace thetad::heli
