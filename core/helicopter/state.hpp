#pragma once

// Indices into the 18-state augmented vector xa (docs/model.md §2, Eq. 28) and the 5 inputs (Eq. 11).
namespace thetad::heli {

inline constexpr int kStateDim = 18;
inline constexpr int kPhysicalStateDim = 14;
inline constexpr int kInputDim = 5;

enum State : int {
  kXp = 0, kYp, kZp,      // inertial NED position (m); altitude = -z_p
  kU, kV, kW,             // body velocity (m/s)
  kPhi, kTheta, kPsi,     // Euler angles, 3-2-1 (rad)
  kP, kQ, kR,             // body rates (rad/s)
  kA1, kB1,               // longitudinal and lateral flapping (rad)
  kXi, kYi, kZi,          // integral states, Eq. 9 (m s)
  kS                      // bias state, Eq. 26
};

enum Input : int {
  kTmr = 0,   // main-rotor thrust (N)
  kPed,       // pedal (rad)
  kCol,       // collective (rad)
  kLon,       // longitudinal cyclic (rad)
  kLat        // lateral cyclic (rad)
};

}  // namespace thetad::heli
