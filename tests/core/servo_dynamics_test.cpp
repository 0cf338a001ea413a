#include "core/sim/servo_dynamics.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace thetad::sim {
namespace {

// The servo lag's position after a unit step: 1 - e^{-t/τ} at every sample; 63.2 % is reached at
// t = τ (to within one sample), and the held input is the position's mean over each period.
TEST(ServoLag, StepResponseHasItsTimeConstant) {
  const double tau = 0.05, period = 1e-3;
  ServoLag lag(Eigen::VectorXd::Constant(1, tau), period);
  Eigen::VectorXd input = Eigen::VectorXd::Zero(1);
  lag.apply(input);  // the servo starts at 0
  double reached = -1.0;
  for (int k = 0; k < 200; ++k) {
    input.setOnes();
    const double start = lag.position()[0];
    lag.apply(input);
    const double t_end = (k + 1) * period;
    EXPECT_NEAR(lag.position()[0], 1.0 - std::exp(-t_end / tau), 1e-12) << k;
    // The mean of 1 - (1 - start) e^{-s/τ} over the period.
    EXPECT_NEAR(input[0], 1.0 - (1.0 - start) * tau / period * (1.0 - std::exp(-period / tau)), 1e-12) << k;
    if (reached < 0.0 && lag.position()[0] >= 1.0 - std::exp(-1.0)) reached = t_end;
  }
  EXPECT_NEAR(reached, tau, period);
}

TEST(ServoLag, ZeroTimeConstantPassesTheInput) {
  ServoLag lag(Eigen::Vector2d(0.0, 0.02), 1e-3);
  Eigen::VectorXd input = Eigen::Vector2d(1.0, 1.0);
  lag.apply(input);
  input = Eigen::Vector2d(3.0, 3.0);
  lag.apply(input);
  EXPECT_EQ(input[0], 3.0);
  EXPECT_LT(input[1], 3.0);
}

TEST(TransportDelay, ShiftsTheCommandByItsSamplesAndHoldsTheFirst) {
  TransportDelay delay(2, 3);
  for (int k = 0; k < 10; ++k) {
    Eigen::VectorXd input = Eigen::Vector2d(k, -k);
    delay.apply(input);
    const double expected = k < 3 ? 0.0 : k - 3;
    EXPECT_EQ(input, Eigen::Vector2d(expected, -expected)) << k;
  }
  delay.reset();
  Eigen::VectorXd input = Eigen::Vector2d(7.0, 7.0);
  delay.apply(input);
  EXPECT_EQ(input, Eigen::Vector2d(7.0, 7.0));
}

// The largest |x| over the last `window` samples of x_{k+1} = x_k + T u_k, u = -K x (sampled, zero-
// order hold) with the command delayed by `delay` samples, from x_0 = 1.
double late_amplitude(double gain, double period, int delay, int samples, int window) {
  TransportDelay line(1, delay);
  double x = 1.0, largest = 0.0;
  for (int k = 0; k < samples; ++k) {
    Eigen::VectorXd u = Eigen::VectorXd::Constant(1, -gain * x);
    line.apply(u);
    x += period * u[0];
    if (k >= samples - window) largest = std::max(largest, std::abs(x));
  }
  return largest;
}

// An integrator under sampled proportional feedback, L(s) = K/s: crossover at ω = K with 90° of
// phase margin, so a delay of (π/2)/K destabilizes it; the zero-order hold adds half a sample. The
// loop must grow at the first delay past d* = (π/2)/(K T) - 1/2 samples, to within one sample.
TEST(TransportDelay, SampledLoopLosesStabilityAtThePredictedDelay) {
  const double gain = 10.0, period = 0.01;
  const double predicted = std::numbers::pi / 2.0 / (gain * period) - 0.5;
  int first_unstable = -1;
  for (int delay = 0; delay <= 40 && first_unstable < 0; ++delay) {
    if (late_amplitude(gain, period, delay, 20000, 1000) > 1.0) first_unstable = delay;
  }
  ASSERT_GE(first_unstable, 0);
  EXPECT_LE(std::abs(first_unstable - predicted), 1.0) << "predicted " << predicted << ", unstable from " << first_unstable;
  EXPECT_LT(late_amplitude(gain, period, first_unstable - 1, 20000, 1000), 1e-3);
}

TEST(ServoSettings, RefuseValuesOutOfRange) {
  ServoSettings settings;
  EXPECT_FALSE(settings.active());
  settings.delay_samples = -1;
  EXPECT_THROW(settings.validate(), Error);
  settings = {};
  settings.time_constant[3] = -0.1;
  EXPECT_THROW(settings.validate(), Error);
}

}  // namespace
}  // namespace thetad::sim
