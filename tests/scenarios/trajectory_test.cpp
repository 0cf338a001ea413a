#include "scenarios/trajectory.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "core/error.hpp"

namespace thetad {
namespace {

// Central-difference velocity of the command (the primitives give positions only).
Eigen::Vector3d velocity(const ReferenceTrajectory& trajectory, double t, double h = 1e-6) {
  return (trajectory.position(t + h) - trajectory.position(t - h)) / (2.0 * h);
}

void expect_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tolerance = 1e-12) {
  EXPECT_LT((actual - expected).norm(), tolerance) << "actual " << actual.transpose() << ", expected "
                                                   << expected.transpose();
}

// Scenario I of docs/model.md §10, altitude h -> z = -h.
PhasedTrajectory scenario_one() {
  PhasedTrajectory trajectory;
  trajectory.append("takeoff", 7.0, Ramp{{0.0, 0.0, -3.5}});
  trajectory.append("hover", 12.0, Hold{});
  trajectory.append("figure8", 62.0, FigureEight{8.0, 4.0, 50.0});
  trajectory.append("hover", 72.0, Hold{});
  trajectory.append("landing", 79.0, Ramp{{0.0, 0.0, 0.0}});
  trajectory.append("on ground", 85.0, Hold{});
  return trajectory;
}

PhasedTrajectory scenario_two() {
  PhasedTrajectory trajectory;
  trajectory.append("takeoff", 7.0, Ramp{{0.0, 0.0, -3.5}});
  trajectory.append("hover", 12.0, Hold{});
  trajectory.append("circle", 72.0, Circle{15.0, 60.0, 2.0, true});
  trajectory.append("hover", 82.0, Hold{});
  return trajectory;
}

TEST(Trajectory, ScenarioOneGivesTheSpecPositionsAtThePhaseBoundaries) {
  const PhasedTrajectory trajectory = scenario_one();
  const Eigen::Vector3d ground = Eigen::Vector3d::Zero(), hover(0.0, 0.0, -3.5);
  expect_near(trajectory.position(0.0), ground);
  expect_near(trajectory.position(3.5), {0.0, 0.0, -1.75});  // 0.5 m/s
  for (const double t : {7.0, 12.0, 62.0, 72.0}) expect_near(trajectory.position(t), hover, 1e-12);
  expect_near(trajectory.position(75.5), {0.0, 0.0, -1.75});
  for (const double t : {79.0, 85.0, 100.0}) expect_near(trajectory.position(t), ground);
  // Continuity: both sides of every boundary agree.
  for (const auto& phase : trajectory.phases()) {
    expect_near(trajectory.position(phase.start_time - 1e-9), trajectory.position(phase.start_time + 1e-9), 1e-7);
  }
}

TEST(Trajectory, FigureEightSpansTheSpecBoxAndStartsTowardsMinusYAndPlusX) {
  const PhasedTrajectory trajectory = scenario_one();
  const Eigen::Vector3d start_velocity = velocity(trajectory, 12.0 + 1e-3);
  EXPECT_LT(start_velocity.y(), 0.0);
  EXPECT_GT(start_velocity.x(), 0.0);
  EXPECT_NEAR(start_velocity.z(), 0.0, 1e-9);
  // Quarter lap: the lobe end at x = +A_x; half lap: back at the crossing; extremes of y at ±A_y.
  expect_near(trajectory.position(12.0 + 12.5), {8.0, 0.0, -3.5}, 1e-9);
  expect_near(trajectory.position(12.0 + 25.0), {0.0, 0.0, -3.5}, 1e-9);
  expect_near(trajectory.position(12.0 + 6.25), {8.0 * std::sin(std::numbers::pi / 4.0), -4.0, -3.5}, 1e-9);
  expect_near(trajectory.position(12.0 + 37.5), {-8.0, 0.0, -3.5}, 1e-9);
}

TEST(Trajectory, FigureEightSpeedsMatchTheSpec) {
  const PhasedTrajectory trajectory = scenario_one();
  // 1.42 m/s at the crossings (start, middle, end of the 8), 1.0 m/s at the lobe ends (the spec's
  // rounded values of ω·sqrt(A_x² + 4A_y²) and 2ωA_y).
  const double omega = 2.0 * std::numbers::pi / 50.0;
  for (const double tau : {1e-4, 25.0, 50.0 - 1e-4}) {
    EXPECT_NEAR(velocity(trajectory, 12.0 + tau).norm(), omega * std::sqrt(64.0 + 64.0), 1e-6);
    EXPECT_NEAR(velocity(trajectory, 12.0 + tau).norm(), 1.42, 5e-3);
  }
  for (const double tau : {12.5, 37.5}) {
    EXPECT_NEAR(velocity(trajectory, 12.0 + tau).norm(), 2.0 * omega * 4.0, 1e-6);
    EXPECT_NEAR(velocity(trajectory, 12.0 + tau).norm(), 1.0, 1e-2);
  }
  // The gentle and stress variants of §8.4.
  PhasedTrajectory gentle, stress;
  gentle.append("figure8", 60.0, FigureEight{5.0, 2.5, 60.0});
  stress.append("figure8", 40.0, FigureEight{10.0, 5.0, 40.0});
  EXPECT_NEAR(velocity(gentle, 1e-4).norm(), 0.74, 5e-3);
  EXPECT_NEAR(velocity(stress, 1e-4).norm(), 2.22, 5e-3);
}

TEST(Trajectory, CircleIsCounterclockwiseWithTheSpecSpeedAndAltitudeDip) {
  const PhasedTrajectory trajectory = scenario_two();
  const Eigen::Vector2d centre(0.0, 15.0);
  double previous_angle = -std::numbers::pi / 2.0;  // the start (0, 0) seen from the centre
  for (double tau = 1.0; tau < 60.0; tau += 1.0) {
    const Eigen::Vector3d p = trajectory.position(12.0 + tau);
    const double angle = std::atan2(p.y() - centre.y(), p.x() - centre.x());
    double increase = angle - previous_angle;
    if (increase < -std::numbers::pi) increase += 2.0 * std::numbers::pi;  // unwrap at ±π
    EXPECT_GT(increase, 0.0) << "at tau = " << tau;
    EXPECT_NEAR((p.head<2>() - centre).norm(), 15.0, 1e-9);
    previous_angle = angle;
  }
  const Eigen::Vector3d first_motion = velocity(trajectory, 12.0 + 1e-3);
  EXPECT_GT(first_motion.x(), 0.0);
  EXPECT_NEAR(velocity(trajectory, 12.0 + 20.0).head<2>().norm(), 15.0 * 2.0 * std::numbers::pi / 60.0, 1e-6);  // 1.57 m/s
  EXPECT_NEAR(velocity(trajectory, 12.0 + 20.0).head<2>().norm(), 1.57, 1e-3);
  expect_near(trajectory.position(12.0 + 30.0), {0.0, 30.0, -1.5}, 1e-9);  // lowest at the half circle
  expect_near(trajectory.position(72.0), {0.0, 0.0, -3.5}, 1e-9);
  expect_near(trajectory.position(82.0), {0.0, 0.0, -3.5}, 1e-9);

  PhasedTrajectory clockwise;
  clockwise.append("circle", 60.0, Circle{15.0, 60.0, 2.0, false});
  EXPECT_LT(clockwise.position(15.0).y(), 0.0);
}

TEST(Trajectory, StepJumpsAtItsStartAndBlendIsSmooth) {
  PhasedTrajectory trajectory({1.0, 2.0, -3.5});
  trajectory.append("hover", 5.0, Hold{});
  trajectory.append("step x", 10.0, Step{{2.0, 2.0, -3.5}});
  trajectory.append("blend", 14.0, Blend{{2.0, 2.0, -5.5}});
  expect_near(trajectory.position(5.0 - 1e-9), {1.0, 2.0, -3.5});
  expect_near(trajectory.position(5.0), {2.0, 2.0, -3.5});
  expect_near(trajectory.position(12.0), {2.0, 2.0, -4.5});  // half way at half time
  expect_near(trajectory.position(14.0), {2.0, 2.0, -5.5});
  EXPECT_LT(velocity(trajectory, 10.0 + 1e-5).norm(), 1e-6);
  EXPECT_LT(velocity(trajectory, 14.0 - 1e-5).norm(), 1e-6);
  EXPECT_NEAR(velocity(trajectory, 12.0).z(), -2.0 * 15.0 / 8.0 / 4.0, 1e-6);  // s'(1/2) = 15/8
}

TEST(Trajectory, AccelerateChangesTheSpeedLinearly) {
  PhasedTrajectory trajectory({0.0, 0.0, -3.5});
  trajectory.append("accelerate", 20.0, Accelerate{Eigen::Vector3d::UnitX(), 0.0, 20.0});
  trajectory.append("cruise", 30.0, Accelerate{Eigen::Vector3d::UnitX(), 20.0, 20.0});
  expect_near(trajectory.position(20.0), {200.0, 0.0, -3.5}, 1e-9);
  expect_near(trajectory.position(30.0), {400.0, 0.0, -3.5}, 1e-9);
  EXPECT_NEAR(velocity(trajectory, 10.0).x(), 10.0, 1e-6);
  // Continuous speed across the boundary when the speeds match.
  EXPECT_NEAR(velocity(trajectory, 20.0 - 1e-3).x(), velocity(trajectory, 20.0 + 1e-3).x(), 1e-2);
  EXPECT_THROW(trajectory.append("bad", 40.0, Accelerate{{1.0, 1.0, 0.0}, 0.0, 1.0}), Error);
}

TEST(Trajectory, SinusoidReturnsToItsStartAfterWholePeriods) {
  PhasedTrajectory trajectory({0.0, 0.0, -3.5});
  trajectory.append("wave", 20.0, Sinusoid{{0.0, 1.0, -0.5}, 10.0});
  expect_near(trajectory.position(2.5), {0.0, 1.0, -4.0}, 1e-12);
  expect_near(trajectory.position(20.0), {0.0, 0.0, -3.5}, 1e-9);
}

TEST(Trajectory, ATimeScaledTrajectoryFliesTheSamePathFaster) {
  PhasedTrajectory trajectory = scenario_one();
  trajectory.append("wave", 95.0, Sinusoid{{0.0, 1.0, -0.5}, 4.0});
  trajectory.append("accelerate", 100.0, Accelerate{Eigen::Vector3d::UnitX(), 0.0, 3.0});
  trajectory.append("step", 102.0, Step{{10.0, 0.0, -3.0}});
  trajectory.append("blend", 105.0, Blend{{10.0, 0.0, -5.0}});
  trajectory.append("circle", 125.0, Circle{15.0, 20.0, 2.0, false});
  for (const double s : {0.5, 1.0, 1.3, 2.0}) {
    SCOPED_TRACE("speed scale " + std::to_string(s));
    const PhasedTrajectory faster = trajectory.time_scaled(s);
    ASSERT_EQ(faster.phases().size(), trajectory.phases().size());
    EXPECT_DOUBLE_EQ(faster.end_time(), 125.0 / s);
    // r_s(t) = r(s t), away from the step's jump, with velocity s times the original's.
    for (double t = 0.05; t < 125.0; t += 0.37) {
      if (std::abs(t - 100.0) < 1e-3) continue;
      expect_near(faster.position(t / s), trajectory.position(t), 1e-9);
      if (std::abs(t - 100.0) < 0.01) continue;
      expect_near(velocity(faster, t / s), s * velocity(trajectory, t), 1e-5 * std::max(1.0, s));
    }
    expect_near(faster.position(200.0 / s), trajectory.position(200.0), 1e-9);
  }
  // The figure 8's crossing speed half way (t = 37 s), ω sqrt(A_x² + 4 A_y²), doubles at twice the speed.
  const double omega = 2.0 * std::numbers::pi / 50.0;
  EXPECT_NEAR(velocity(trajectory.time_scaled(2.0), 37.0 / 2.0).norm(), 2.0 * omega * std::sqrt(64.0 + 64.0), 1e-6);
  EXPECT_THROW(trajectory.time_scaled(0.0), Error);
  EXPECT_THROW(trajectory.time_scaled(-1.0), Error);
  EXPECT_THROW(trajectory.time_scaled(std::nan("")), Error);
}

// Turned by a course about its start: every offset from the start, velocity and acceleration
// turned (north towards east), heights as they were; turns compose, and with the speed scale.
TEST(Trajectory, ATurnedTrajectoryFliesThePathOnAnotherCourse) {
  PhasedTrajectory trajectory(Eigen::Vector3d(1.0, 2.0, -3.5));
  trajectory.append("accelerate", 10.0, Accelerate{Eigen::Vector3d::UnitX(), 0.0, 5.0});
  trajectory.append("climb", 14.0, Blend{{0.0, 0.0, -2.0}});
  trajectory.append("circle", 30.0, Circle{6.0, 16.0, 1.0, false});
  const double course = std::numbers::pi / 2.0;  // east
  const PhasedTrajectory east = trajectory.turned(course);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(course, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (double t = -1.0; t < 35.0; t += 0.41) {
    expect_near(east.position(t) - trajectory.start_position(),
                turn * (trajectory.position(t) - trajectory.start_position()), 1e-12);
    expect_near(east.velocity(t), turn * trajectory.velocity(t), 1e-12);
    expect_near(east.acceleration(t), turn * trajectory.acceleration(t), 1e-12);
    EXPECT_NEAR(east.position(t).z(), trajectory.position(t).z(), 1e-12);
  }
  // The leg north at 5 m/s now goes east.
  expect_near(east.velocity(10.0 - 1e-9), Eigen::Vector3d(0.0, 5.0, 0.0), 1e-6);
  expect_near(east.end_position() - trajectory.start_position(),
              turn * (trajectory.end_position() - trajectory.start_position()), 1e-12);
  // Two quarter turns make a half; a turned trajectory keeps its turn when flown faster.
  expect_near(east.turned(course).position(12.0), trajectory.turned(std::numbers::pi).position(12.0), 1e-12);
  expect_near(east.time_scaled(2.0).position(6.0), east.position(12.0), 1e-9);
  // No turn asked, nothing recomputed: the commands are those of the file, bit for bit.
  EXPECT_EQ(trajectory.time_scaled(1.0).position(12.3), trajectory.position(12.3));
  EXPECT_THROW(trajectory.turned(std::nan("")), Error);
}

TEST(Trajectory, RejectsPhasesThatDoNotMoveForwardAndBadPeriods) {
  PhasedTrajectory trajectory;
  trajectory.append("hover", 5.0, Hold{});
  EXPECT_THROW(trajectory.append("back", 4.0, Hold{}), Error);
  EXPECT_THROW(trajectory.append("empty", 5.0, Hold{}), Error);
  EXPECT_THROW(trajectory.append("eight", 10.0, FigureEight{8.0, 4.0, 0.0}), Error);
  EXPECT_THROW(trajectory.append("circle", 10.0, Circle{15.0, -1.0, 2.0, true}), Error);
  EXPECT_EQ(trajectory.phases().size(), 1u);
}

}  // namespace
}  // namespace thetad
