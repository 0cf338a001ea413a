// The flight computer in the loop (docs/model.md §15.7): its schedule (which samples compute, when
// each result arrives, what overruns do), zero latency as no computer at all, and a sampled loop
// that loses stability at the latency the theory predicts.
#include "core/sim/flight_computer.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/sim/helicopter_disturbances.hpp"
#include "core/sim/simulator.hpp"
#include "tests/core/hover_trim.hpp"
#include "tests/test_plants.hpp"

namespace thetad::sim {
namespace {

using Latency = FlightComputerSettings::Latency;
using Overrun = FlightComputerSettings::Overrun;

FlightComputerSettings fixed_latency(double seconds, Overrun overrun = Overrun::skip_next) {
  FlightComputerSettings settings;
  settings.latency = Latency::fixed;
  settings.fixed = seconds;
  settings.overrun = overrun;
  return settings;
}

TEST(FlightComputer, ALatencyWithinThePeriodArrivesWithinItsOwnPeriod) {
  FlightComputer computer(fixed_latency(0.4e-3), 1e-3);
  ASSERT_TRUE(computer.free_at(0));
  EXPECT_EQ(computer.start(0, 0), 0.0);  // the first input is computed before the flight
  EXPECT_EQ(computer.arrival(0), 0.0);
  for (std::int64_t k = 1; k < 5; ++k) {
    ASSERT_TRUE(computer.free_at(k));
    EXPECT_EQ(computer.start(k, 0), 0.4e-3);
    const std::optional<double> arrival = computer.arrival(k);
    ASSERT_TRUE(arrival);
    EXPECT_NEAR(*arrival, 0.4e-3, 1e-15);
    EXPECT_FALSE(computer.arrival(k));  // delivered once
  }
  EXPECT_EQ(computer.counts().missed_deadlines, 0);
  EXPECT_EQ(computer.counts().computations, 5);
  EXPECT_NEAR(computer.counts().mean_latency, 4 * 0.4e-3 / 5, 1e-15);
}

TEST(FlightComputer, ALatencyOfExactlyOnePeriodArrivesAtTheNextSampleWithoutAMiss) {
  FlightComputer computer(fixed_latency(1e-3), 1e-3);
  computer.start(0, 0);
  computer.arrival(0);
  computer.start(1, 0);
  EXPECT_FALSE(computer.arrival(1));
  ASSERT_TRUE(computer.free_at(2));
  EXPECT_EQ(computer.arrival(2), 0.0);
  EXPECT_EQ(computer.counts().missed_deadlines, 0);
}

// Skip-next: a computation of 2.5 periods started at sample 1 arrives half-way through sample 3's
// period; samples 2 and 3 start none; the next starts at sample 4.
TEST(FlightComputer, SkipNextAppliesALateResultWhenReadyAndSkipsTheSamplesItOverran) {
  FlightComputer computer(fixed_latency(2.5e-3), 1e-3);
  std::vector<std::int64_t> started;
  std::vector<double> arrivals;
  for (std::int64_t k = 0; k < 11; ++k) {
    if (computer.free_at(k)) {
      computer.start(k, 0);
      started.push_back(k);
    } else {
      computer.skip();
    }
    if (const std::optional<double> arrival = computer.arrival(k)) arrivals.push_back(static_cast<double>(k) + *arrival / 1e-3);
  }
  EXPECT_EQ(started, (std::vector<std::int64_t>{0, 1, 4, 7, 10}));
  ASSERT_EQ(arrivals.size(), 4u);
  EXPECT_NEAR(arrivals[1], 3.5, 1e-9);
  EXPECT_NEAR(arrivals[3], 9.5, 1e-9);
  const ComputerCounts counts = computer.counts();
  EXPECT_EQ(counts.missed_deadlines, 4);
  EXPECT_EQ(counts.longest_missed_run, 4);
  EXPECT_EQ(counts.skipped_samples, 6);
  EXPECT_EQ(counts.aborted, 0);
  EXPECT_EQ(counts.max_latency, 2.5e-3);
}

TEST(FlightComputer, AbortDropsALateResultAndStartsTheNextOnTime) {
  FlightComputer computer(fixed_latency(2.5e-3, Overrun::abort), 1e-3);
  int arrivals = 0;
  for (std::int64_t k = 0; k < 10; ++k) {
    ASSERT_TRUE(computer.free_at(k)) << k;
    computer.start(k, 0);
    if (computer.arrival(k)) ++arrivals;
  }
  EXPECT_EQ(arrivals, 1);  // the first, computed before the flight
  EXPECT_EQ(computer.counts().aborted, 9);
  EXPECT_EQ(computer.counts().missed_deadlines, 9);
  EXPECT_EQ(computer.counts().skipped_samples, 0);
}

TEST(FlightComputer, MeasuredAndStepTimeLatenciesAreScaled) {
  FlightComputerSettings measured;
  measured.latency = Latency::measured;
  measured.slowdown = 30.0;
  FlightComputer a(measured, 1e-3);
  a.start(0, 0);
  EXPECT_NEAR(a.start(1, 20000), 30.0 * 20e-6, 1e-18);
  FlightComputerSettings step_time;
  step_time.latency = Latency::step_time;
  step_time.slowdown = 100.0;
  step_time.step_time = 4e-5;
  FlightComputer b(step_time, 1e-3);
  b.start(0, 0);
  EXPECT_NEAR(b.start(1, 123), 4e-3, 1e-18);
}

TEST(FlightComputerSettings, RefuseValuesOutOfRange) {
  EXPECT_NO_THROW(FlightComputerSettings{}.validate());
  EXPECT_THROW(fixed_latency(-1e-3).validate(), Error);
  EXPECT_THROW(fixed_latency(61.0).validate(), Error);
  FlightComputerSettings settings;
  settings.slowdown = 0.0;
  EXPECT_THROW(settings.validate(), Error);
  settings = {};
  settings.latency = Latency::step_time;
  EXPECT_THROW(settings.validate(), Error);  // no step time
  SimulationSettings simulation = SimulationSettings::ideal();
  simulation.computer.latency = Latency::measured;
  simulation.measure_compute_time = false;
  EXPECT_THROW(simulation.validate(), Error);
}

// u = -K x on the integrator x' = u, sampled at T with zero-order hold, its input arriving τ < T
// after each sample: x_{k+1} = x_k + (T - τ) u_k + τ u_{k-1}, so z² - (1 - K(T - τ)) z + Kτ = 0,
// stable while Kτ < 1 (Jury; KT = 1.5 here). The plant step is split where the input arrives, so
// the flight is that difference equation.
class Proportional final : public ControlLaw {
 public:
  explicit Proportional(double gain) : gain_(gain) {}
  std::string name() const override { return "proportional"; }
  void reset(const Eigen::VectorXd&, double) override {}
  void control(double, const Eigen::Ref<const Eigen::VectorXd>& x, const Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    u[0] = -gain_ * x[0];
  }

 private:
  double gain_;
};

constexpr double kPeriod = 0.01, kGain = 1.5 / kPeriod;

RunResult integrator_flight(const FlightComputerSettings& computer, double duration = 2.0) {
  const thetad::LinearPlant plant(Eigen::MatrixXd::Zero(1, 1), Eigen::MatrixXd::Ones(1, 1));
  NoDisturbances disturbances(plant);
  SimulationSettings settings = SimulationSettings::ideal();
  settings.dt = kPeriod / 10.0;
  settings.controller_period_steps = 10;
  settings.duration = duration;
  settings.measure_compute_time = false;
  settings.computer = computer;
  Proportional law(kGain);
  return simulate(law, disturbances, FixedPosition(Eigen::Vector3d::Zero()), Eigen::VectorXd::Ones(1), settings);
}

// The decay or growth per sample of the logged state over the second half of the flight.
double rate_per_sample(const RunResult& run) {
  const std::size_t width = run.log.columns.size(), rows = run.log.values.size() / width;
  const auto largest = [&](std::size_t from, std::size_t to) {
    double value = 0.0;
    for (std::size_t r = from; r < to; ++r) value = std::max(value, std::abs(run.log.values[r * width + 1]));
    return value;
  };
  const std::size_t half = rows / 2;
  return std::exp(std::log(largest(half, rows) / largest(0, half)) / static_cast<double>(half));
}

TEST(FlightComputer, SampledLoopLosesStabilityAtThePredictedLatency) {
  const double boundary = 1.0 / kGain;  // Kτ = 1
  for (const double share : {0.5, 0.9, 0.97, 1.03, 1.1}) {
    const double tau = share * boundary;
    const RunResult run = integrator_flight(fixed_latency(tau));
    ASSERT_EQ(run.summary.status, RunStatus::completed) << share;
    // Complex roots (K(T - τ) - 1)² < 4Kτ here: |z| = √(Kτ).
    EXPECT_NEAR(rate_per_sample(run), std::sqrt(kGain * tau), 0.01) << share;
    EXPECT_EQ(run.summary.computer->missed_deadlines, 0);
  }
}

TEST(FlightComputer, AnAbortedComputerHoldsTheFirstInput) {
  const RunResult run = integrator_flight(fixed_latency(2.5 * kPeriod, Overrun::abort), 0.5);
  const std::size_t width = run.log.columns.size();
  const std::size_t last = run.log.values.size() / width - 1;
  // x' = u_0 = -K from x = 1: x_k = 1 - K k T.
  EXPECT_NEAR(run.log.values[last * width + 1], 1.0 - kGain * static_cast<double>(last) * kPeriod, 1e-9);
  EXPECT_EQ(run.summary.computer->aborted, 49);
  EXPECT_EQ(run.log.columns[width - 3].header(), "computation_latency_s");
  EXPECT_EQ(run.log.columns[width - 2].header(), "sample_skipped");
}

TEST(FlightComputer, SkippedSamplesAreLoggedAndCounted) {
  const RunResult run = integrator_flight(fixed_latency(2.5 * kPeriod), 0.5);
  const ComputerCounts counts = *run.summary.computer;
  EXPECT_EQ(counts.computations, 1 + 17);  // samples 0, 1, 4, ..., 49
  EXPECT_EQ(counts.skipped_samples, 50 - 18);
  EXPECT_EQ(counts.longest_missed_run, 17);
  const std::size_t width = run.log.columns.size();
  EXPECT_EQ(run.log.values[2 * width + width - 2], 1.0);  // sample 2: busy
  EXPECT_EQ(run.log.values[4 * width + width - 2], 0.0);
  EXPECT_EQ(run.log.values[4 * width + width - 3], 2.5 * kPeriod);
}

// A controller that feeds back the measured state, so that any change in what it sees or when its
// input acts would show in every later sample.
class TrimFeedback final : public ControlLaw {
 public:
  std::string name() const override { return "trim_feedback"; }
  void reset(const Eigen::VectorXd&, double) override {}
  void control(double, const Eigen::Ref<const Eigen::VectorXd>& x, const Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    u = trim_;
    u.array() -= 1e-3 * x.head(5).array();
  }

 private:
  Eigen::VectorXd trim_ = thetad::testing::hover_trim_input();
};

TEST(FlightComputer, ZeroLatencyIsNoComputerBitForBit) {
  SimulationSettings settings = SimulationSettings::paper();
  settings.duration = 0.3;
  settings.measure_compute_time = false;
  TrimFeedback law;
  const RunResult none = simulate(law, thetad::testing::kHoverPoint, thetad::testing::hover_trim_state(), settings);
  settings.computer = fixed_latency(0.0);
  const RunResult zero = simulate(law, thetad::testing::kHoverPoint, thetad::testing::hover_trim_state(), settings);
  ASSERT_FALSE(none.summary.computer);
  ASSERT_TRUE(zero.summary.computer);
  EXPECT_EQ(zero.summary.computer->missed_deadlines, 0);
  EXPECT_EQ(none.summary.cost, zero.summary.cost);
  EXPECT_EQ(none.summary.rms_tracking_error, zero.summary.rms_tracking_error);
  // The same rows less the computer's two columns (before the step time, the last).
  const std::size_t width = none.log.columns.size();
  ASSERT_EQ(zero.log.columns.size(), width + 2);
  std::vector<double> without;
  for (std::size_t i = 0; i < zero.log.values.size(); ++i) {
    const std::size_t column = i % (width + 2);
    if (column != width - 1 && column != width) without.push_back(zero.log.values[i]);
  }
  EXPECT_EQ(without, none.log.values);
}

}  // namespace
}  // namespace thetad::sim
