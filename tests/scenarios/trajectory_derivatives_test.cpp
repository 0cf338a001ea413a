// The commanded velocity and acceleration every controller may use: the exact derivatives of each
// trajectory primitive, checked against central differences of its position, right-continuous at
// phase boundaries, and scaled as the speed scale says.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "scenarios/trajectory.hpp"

namespace thetad {
namespace {

// One phase of every kind, back to back, each starting away from the origin.
PhasedTrajectory every_motion() {
  PhasedTrajectory trajectory(Eigen::Vector3d(1.0, -2.0, -3.0));
  trajectory.append("ramp", 4.0, Ramp{{2.0, 1.0, -4.0}});
  trajectory.append("hold", 5.0, Hold{});
  trajectory.append("step", 6.0, Step{{2.5, 1.0, -4.0}});
  trajectory.append("blend", 9.0, Blend{{0.0, 3.0, -2.0}});
  trajectory.append("accelerate", 13.0, Accelerate{Eigen::Vector3d(0.6, 0.0, -0.8), 1.0, 3.0});
  trajectory.append("sinusoid", 20.0, Sinusoid{{0.5, -1.0, 0.25}, 3.0});
  trajectory.append("figure8", 45.0, FigureEight{8.0, 4.0, 25.0});
  trajectory.append("circle", 75.0, Circle{15.0, 30.0, 2.0, false});
  return trajectory;
}

// Interior times of every phase (away from the boundaries, where the derivatives jump).
std::vector<double> interior_times(const PhasedTrajectory& trajectory) {
  std::vector<double> times;
  for (const auto& phase : trajectory.phases()) {
    for (double f : {0.13, 0.5, 0.87}) times.push_back(phase.start_time + f * (phase.end_time - phase.start_time));
  }
  return times;
}

TEST(TrajectoryDerivatives, AreThoseOfThePositionEverywhereInsideAPhase) {
  const PhasedTrajectory trajectory = every_motion();
  const double h = 1e-5;
  for (double t : interior_times(trajectory)) {
    const Eigen::Vector3d velocity = (trajectory.position(t + h) - trajectory.position(t - h)) / (2.0 * h);
    const Eigen::Vector3d acceleration =
        (trajectory.position(t + h) - 2.0 * trajectory.position(t) + trajectory.position(t - h)) / (h * h);
    const Eigen::Vector3d velocity_of_velocity = (trajectory.velocity(t + h) - trajectory.velocity(t - h)) / (2.0 * h);
    EXPECT_LT((trajectory.velocity(t) - velocity).norm(), 1e-8 * (1.0 + velocity.norm())) << "t = " << t;
    EXPECT_LT((trajectory.acceleration(t) - velocity_of_velocity).norm(), 1e-7 * (1.0 + acceleration.norm()))
        << "t = " << t;
    // The second difference of the position is the same acceleration (to its rounding, h² apart).
    EXPECT_LT((trajectory.acceleration(t) - acceleration).norm(), 2e-4) << "t = " << t;
  }
}

TEST(TrajectoryDerivatives, AtABoundaryAreTheNextPhasesAndStillAfterTheEnd) {
  const PhasedTrajectory trajectory = every_motion();
  // 4 s: the ramp ends, the hold begins (standing still); 9 s: the blend ends, the acceleration
  // begins at its start speed 1 m/s along its direction.
  EXPECT_EQ(trajectory.velocity(4.0), Eigen::Vector3d::Zero());
  EXPECT_LT((trajectory.velocity(9.0) - Eigen::Vector3d(0.6, 0.0, -0.8)).norm(), 1e-15);
  EXPECT_LT((trajectory.acceleration(9.0) - 0.5 * Eigen::Vector3d(0.6, 0.0, -0.8)).norm(), 1e-15);
  // Just before 4 s: the ramp's velocity, (to − start) / duration.
  EXPECT_LT((trajectory.velocity(4.0 - 1e-9) - Eigen::Vector3d(1.0, 3.0, -1.0) / 4.0).norm(), 1e-15);
  // A step jumps the position, not the derivatives: inside it the command stands still.
  EXPECT_EQ(trajectory.velocity(5.0), Eigen::Vector3d::Zero());
  // Before the start and from the last phase's end on, the command holds still.
  EXPECT_EQ(trajectory.velocity(-1.0), Eigen::Vector3d::Zero());
  EXPECT_EQ(trajectory.velocity(75.0), Eigen::Vector3d::Zero());
  EXPECT_EQ(trajectory.acceleration(80.0), Eigen::Vector3d::Zero());
}

TEST(TrajectoryDerivatives, FollowTheSpeedScale) {
  const PhasedTrajectory trajectory = every_motion();
  for (double s : {0.5, 2.0, 3.7}) {
    const PhasedTrajectory faster = trajectory.time_scaled(s);
    for (double t : interior_times(trajectory)) {
      EXPECT_LT((faster.velocity(t / s) - s * trajectory.velocity(t)).norm(), 1e-12 * s * (1.0 + trajectory.velocity(t).norm()))
          << "s = " << s << ", t = " << t;
      EXPECT_LT((faster.acceleration(t / s) - s * s * trajectory.acceleration(t)).norm(),
                1e-12 * s * s * (1.0 + trajectory.acceleration(t).norm()))
          << "s = " << s << ", t = " << t;
    }
  }
}

// The figure 8 of scenario I: its speed at the crossing is ω·sqrt(A_x² + 4A_y²) (docs/model.md §10).
TEST(TrajectoryDerivatives, TheFigureEightCrossesAtItsKnownSpeed) {
  PhasedTrajectory trajectory;
  trajectory.append("figure8", 50.0, FigureEight{8.0, 4.0, 50.0});
  const double omega = 2.0 * std::numbers::pi / 50.0;
  EXPECT_NEAR(trajectory.velocity(0.0).norm(), omega * std::sqrt(64.0 + 64.0), 1e-14);
  EXPECT_NEAR(trajectory.velocity(25.0).norm(), omega * std::sqrt(64.0 + 64.0), 1e-13);
}

}  // namespace
}  // namespace thetad
