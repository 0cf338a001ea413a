#include "core/helicopter/rotor_speed.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace thetad::heli {
namespace {

const Parameters kNominal = Parameters::nominal();
const double kHoverThrust = kNominal.mass * kNominal.gravity;  // 80.442 N

TEST(RotorSpeed, RestValueOfSpec) {
  // docs/model.md §4.2 / §10.2: T_mr = m g at rest -> 171.927 rad/s.
  EXPECT_NEAR(main_rotor_speed(kNominal, kHoverThrust, 0.0, 0.0, kNominal.omega_nom), 171.927, 5e-4);
}

TEST(RotorSpeed, SanityTableOfSpec) {
  // docs/model.md §4.2: same thrust at V_h = 0, 1, 2, 3, 5, 10, 20 m/s (printed to 0.1 rad/s, 0.01 at 0).
  const double speeds[] = {0, 1, 2, 3, 5, 10, 20};
  const double printed[] = {171.93, 169.7, 163.3, 153.2, 126.8, 74.3, 37.8};
  for (int i = 0; i < 7; ++i) {
    const double tolerance = i == 0 ? 5e-3 : 5e-2;
    EXPECT_NEAR(main_rotor_speed(kNominal, kHoverThrust, speeds[i], 0.0, kNominal.omega_nom), printed[i], tolerance)
        << "V_h = " << speeds[i];
  }
}

TEST(RotorSpeed, RoundTripThrustToSpeedToThrust) {
  double worst = 0.0;
  for (double vh = 0.0; vh <= 5.0 + 1e-12; vh += 0.25) {
    for (double w_a : {-3.0, -1.0, 0.0, 0.5, 2.0}) {
      for (double thrust = 20.0; thrust <= 150.0 + 1e-12; thrust += 5.0) {
        const double omega = main_rotor_speed(kNominal, thrust, vh, w_a, kNominal.omega_nom);
        const double back = main_rotor_thrust(kNominal, omega, vh, w_a);
        worst = std::max(worst, std::abs(back - thrust) / thrust);
      }
    }
  }
  EXPECT_LE(worst, 1e-10);
  std::cout << "max relative round-trip error T -> Omega -> T: " << worst << "\n";
}

TEST(RotorSpeed, ConvergedToTwelveDigits) {
  // In the monotonic case the root is bracketed by Omega (1 -/+ 1e-11): g changes sign there.
  for (double vh : {0.0, 1.3, 4.7}) {
    for (double thrust : {25.0, 80.442, 140.0}) {
      const double omega = main_rotor_speed(kNominal, thrust, vh, 0.0, kNominal.omega_nom);
      EXPECT_LT(main_rotor_thrust(kNominal, omega * (1 - 1e-11), vh, 0.0), thrust);
      EXPECT_GT(main_rotor_thrust(kNominal, omega * (1 + 1e-11), vh, 0.0), thrust);
    }
  }
}

TEST(RotorSpeed, FastDescentPicksRootNearestHint) {
  // V_h = 0, w_a = 10 m/s: g = k Omega |c Omega - w_a| has a local maximum (~104 N) at
  // Omega = w_a/(2c) ~ 195.5 and a minimum (-T) at w_a/c ~ 391: three roots for T = 50 N.
  const double thrust = 50.0, w_a = 10.0;
  const double low = main_rotor_speed(kNominal, thrust, 0.0, w_a, 20.0);
  const double mid = main_rotor_speed(kNominal, thrust, 0.0, w_a, 300.0);
  const double high = main_rotor_speed(kNominal, thrust, 0.0, w_a, 600.0);
  EXPECT_LT(low, 195.0);
  EXPECT_GT(mid, 196.0);
  EXPECT_LT(mid, 391.0);
  EXPECT_GT(high, 392.0);
  for (double omega : {low, mid, high}) {
    EXPECT_NEAR(main_rotor_thrust(kNominal, omega, 0.0, w_a), thrust, 1e-9 * thrust);
  }
  // Each hint gets the nearest of the three.
  EXPECT_DOUBLE_EQ(main_rotor_speed(kNominal, thrust, 0.0, w_a, low + 1.0), low);
  EXPECT_DOUBLE_EQ(main_rotor_speed(kNominal, thrust, 0.0, w_a, mid - 1.0), mid);
}

TEST(RotorSpeed, BadThrustThrows) {
  EXPECT_THROW(main_rotor_speed(kNominal, -1.0, 0.0, 0.0, 167.0), Error);
  EXPECT_THROW(main_rotor_speed(kNominal, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0, 167.0), Error);
  EXPECT_THROW(main_rotor_speed(kNominal, std::numeric_limits<double>::infinity(), 0.0, 0.0, 167.0), Error);
}

TEST(RotorSpeed, NoRootInBracketThrowsWithThrustAndBracket) {
  // A4 gives ~1.1 N at 20 rad/s in hover: 0.5 N has no root in the bracket; nor has 1e5 N.
  for (double thrust : {0.5, 1e5}) {
    try {
      main_rotor_speed(kNominal, thrust, 0.0, 0.0, 167.0);
      ADD_FAILURE() << "no exception for T = " << thrust;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("[20, 600]"), std::string::npos) << message;
      EXPECT_NE(message.find("T_mr"), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace thetad::heli
