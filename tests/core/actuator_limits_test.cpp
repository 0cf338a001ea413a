#include "core/sim/actuator_limits.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "controllers/lqr_schedule_design.hpp"
#include "core/error.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "tests/error_message.hpp"

namespace thetad::sim {
namespace {

using namespace heli;

constexpr double kDegree = std::numbers::pi / 180.0;

// Slams every input from far below its range to far above it every 20 ms: the worst a
// controller can ask of the servos.
class BangBang final : public ControlLaw {
 public:
  std::string name() const override { return "bang_bang"; }
  void reset(const Eigen::VectorXd&, double) override {}
  void control(double t, const Eigen::Ref<const Eigen::VectorXd>&, const Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    const double sign = std::fmod(t, 0.04) < 0.02 ? 1.0 : -1.0;
    u << 80.0 + sign * 500.0, sign * 3.0, sign * 3.0, sign * 3.0, sign * 3.0;
  }
};

constexpr int kAppliedColumn = 4 + 2 * kStateDim + kInputDim;  // t, x_c, y_c, z_c, states, measured, commanded
constexpr int kFlagColumn = kAppliedColumn + kInputDim;

RunResult fly_bang_bang(bool limits_on, bool actuator_noise) {
  SimulationSettings settings = SimulationSettings::ideal();
  settings.noise.actuator = actuator_noise;
  settings.duration = 0.07;
  settings.measure_compute_time = false;
  settings.actuator_limits.enabled = limits_on;
  // The bang-bang rolls the helicopter over in ~0.08 s: no attitude, rate or speed limit may end
  // these 0.07 s.
  settings.limits.max_body_rate = 1e6;
  settings.limits.max_speed = 1e6;
  settings.limits.max_attitude = 1.55;
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(kStateDim);
  x0[kZp] = -3.5;
  x0[kS] = 1.0;
  BangBang law;
  return simulate(law, FixedPosition(Eigen::Vector3d(0.0, 0.0, -3.5)), x0, settings);
}

TEST(ActuatorLimitsTest, LogColumnsAreWhereTheTestLooks) {
  EXPECT_EQ(helicopter_log_schema()[kAppliedColumn].header(), "app_T_mr_N");
  EXPECT_EQ(helicopter_log_schema()[kFlagColumn].header(), "sat_T_mr_flag");
}

TEST(ActuatorLimitsTest, SaturatedInputNeverExceedsItsBound) {
  const ActuatorLimits limits = ActuatorLimits::x_cell();
  for (const bool noise : {false, true}) {
    const RunResult run = fly_bang_bang(true, noise);
    ASSERT_EQ(run.summary.status, RunStatus::completed) << run.summary.reason;
    ASSERT_EQ(run.log.rows(), 70);
    for (Eigen::Index i = 0; i < run.log.rows(); ++i) {
      const auto row = run.log.row(i);
      for (int k = 0; k < kInputDim; ++k) {
        EXPECT_GE(row[kAppliedColumn + k], limits.lower[k]) << "row " << i << " channel " << k;
        EXPECT_LE(row[kAppliedColumn + k], limits.upper[k]) << "row " << i << " channel " << k;
      }
    }
    // Every channel was asked for more than its range, at every sample.
    EXPECT_EQ(run.summary.saturation.samples_limited, run.summary.controller_samples);
    for (int k = 0; k < kInputDim; ++k) EXPECT_GT(run.summary.saturation.magnitude[k], 0) << "channel " << k;
  }
}

TEST(ActuatorLimitsTest, RateLimitHoldsBetweenSamples) {
  const ActuatorLimits limits = ActuatorLimits::x_cell();
  const double period = SimulationSettings{}.controller_period();
  const RunResult run = fly_bang_bang(true, true);
  bool rate_flagged = false;
  for (Eigen::Index i = 1; i < run.log.rows(); ++i) {
    for (int k = 0; k < kInputDim; ++k) {
      const double step = std::abs(run.log.row(i)[kAppliedColumn + k] - run.log.row(i - 1)[kAppliedColumn + k]);
      EXPECT_LE(step, limits.rate[k] * period * (1.0 + 1e-12)) << "row " << i << " channel " << k;
      rate_flagged = rate_flagged || run.log.row(i)[kFlagColumn + k] == 2.0;
    }
  }
  // The bang-bang crosses the range every 20 ms, faster than the 150 ms the servos need.
  EXPECT_TRUE(rate_flagged);
  for (int k = 0; k < kInputDim; ++k) EXPECT_GT(run.summary.saturation.rate[k], 0) << "channel " << k;
}

TEST(ActuatorLimitsTest, OffMeansOff) {
  const RunResult run = fly_bang_bang(false, false);
  for (Eigen::Index i = 0; i < run.log.rows(); ++i) {
    const auto row = run.log.row(i);
    for (int k = 0; k < kInputDim; ++k) {
      EXPECT_EQ(row[kAppliedColumn + k], row[kAppliedColumn - kInputDim + k]) << "row " << i;  // applied = commanded
      EXPECT_EQ(row[kFlagColumn + k], 0.0);
    }
  }
  EXPECT_EQ(run.summary.saturation.samples_limited, 0);
  for (int k = 0; k < kInputDim; ++k) {
    EXPECT_EQ(run.summary.saturation.magnitude[k], 0);
    EXPECT_EQ(run.summary.saturation.rate[k], 0);
  }
}

TEST(ActuatorLimitsTest, LimiterClampsMagnitudeFirstThenRate) {
  ActuatorLimits limits = ActuatorLimits::x_cell();
  limits.lower.setConstant(-1.0);
  limits.upper.setConstant(1.0);
  limits.rate.setConstant(10.0);  // 0.1 per 10 ms sample
  ActuatorLimiter limiter(limits, 0.01);
  Eigen::VectorXd u = Eigen::VectorXd::Constant(kInputDim, 5.0);
  limiter.apply(u);  // the first sample: magnitude only
  EXPECT_TRUE(u.isApproxToConstant(1.0));
  EXPECT_EQ(limiter.last_flags(), 0x1fu);
  u.setConstant(-5.0);
  limiter.apply(u);  // then at most 0.1 per sample
  EXPECT_TRUE(u.isApproxToConstant(0.9));
  EXPECT_EQ(limiter.last_flags(), 0x1fu << kInputDim);
  u.setConstant(0.85);
  limiter.apply(u);  // within both: untouched
  EXPECT_TRUE(u.isApproxToConstant(0.85));
  EXPECT_EQ(limiter.last_flags(), 0u);
  EXPECT_EQ(limiter.counts().magnitude[0], 1);
  EXPECT_EQ(limiter.counts().rate[0], 1);
  EXPECT_EQ(limiter.counts().samples_limited, 2);
  limiter.reset();
  EXPECT_EQ(limiter.counts().samples_limited, 0);
}

TEST(ActuatorLimitsTest, InvalidLimitsNameTheChannel) {
  SimulationSettings settings;
  settings.actuator_limits.enabled = true;
  settings.actuator_limits.upper[kCol] = settings.actuator_limits.lower[kCol];
  EXPECT_NE(testing::error_message([&] { settings.validate(); }).find("delta_col"), std::string::npos);
  settings.actuator_limits = ActuatorLimits::x_cell();
  settings.actuator_limits.rate[kLat] = 0.0;
  EXPECT_NE(testing::error_message([&] { settings.validate(); }).find("delta_lat: the rate limit must be positive"),
            std::string::npos);
  settings.actuator_limits.enabled = false;  // unused limits are not checked
  EXPECT_NO_THROW(settings.validate());
}

// The documented defaults: thrust up to T_max, the X-Cell's collective range, and a 100 % margin
// over steady flight (forward and rearward to 20 m/s, every direction to 4 m/s) for the pedal and
// the cyclics, from fresh trims.
TEST(ActuatorLimitsTest, DefaultsHoldSteadyFlightWithTheirMargin) {
  const Parameters p = Parameters::nominal();
  const ActuatorLimits limits = ActuatorLimits::x_cell(p);
  EXPECT_DOUBLE_EQ(limits.upper[kTmr], p.max_main_rotor_thrust());
  EXPECT_NEAR(limits.upper[kTmr], 212.96, 0.01);  // docs/model.md §5
  EXPECT_EQ(limits.lower[kTmr], 0.0);
  EXPECT_NEAR((limits.lower[kCol] + p.collective_trim_offset) / kDegree, -6.0, 1e-12);
  EXPECT_NEAR((limits.upper[kCol] + p.collective_trim_offset) / kDegree, 10.0, 1e-12);
  for (int k = 0; k < kInputDim; ++k)
    EXPECT_NEAR(limits.rate[k] * ActuatorLimits::kFullRangeTime, limits.upper[k] - limits.lower[k], 1e-9);

  const Helicopter model;
  const DesignDefaults weights = model.design_defaults();
  const LqrScheduleTable table =
      design_lqr_schedule(model, LqrScheduleGrid::envelope(), weights.state_weights, weights.input_weights);
  double pedal = 0.0, cyclic = 0.0, thrust = 0.0;
  int counted = 0;
  for (const auto& point : table.points) {
    const bool body_axis = std::abs(point.course) < 1e-12 || std::abs(point.course - std::numbers::pi) < 1e-12;
    if (!body_axis && point.speed > 4.0) continue;
    const Eigen::VectorXd& u = point.point.input;
    pedal = std::max(pedal, std::abs(u[kPed]));
    cyclic = std::max({cyclic, std::abs(u[kLon]), std::abs(u[kLat])});
    thrust = std::max(thrust, u[kTmr]);
    ++counted;
  }
  EXPECT_EQ(counted, 12 * 2 * 3 + 5 * 6 * 3);  // 12 speeds on the axis, 5 speeds <= 4 m/s off it
  EXPECT_DOUBLE_EQ(limits.upper[kPed], std::ceil(200.0 * pedal) / 100.0);
  EXPECT_DOUBLE_EQ(limits.upper[kLon], std::ceil(200.0 * cyclic) / 100.0);
  EXPECT_DOUBLE_EQ(limits.upper[kLat], limits.upper[kLon]);
  for (const int k : {kPed, kLon, kLat}) EXPECT_EQ(limits.lower[k], -limits.upper[k]);
  EXPECT_LE(2.0 * thrust, limits.upper[kTmr]);
}

}  // namespace
}  // namespace thetad::sim
