// The closed-loop objective: θ–D flights over seeded draws through the experiment library, the
// same for any number of workers, scored by the mean cost or RMS error, a diverged draw by +∞;
// and its search within an evaluation budget.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tuning/closed_loop.hpp"

namespace thetad::tuning {
namespace {

using Eigen::VectorXd;
using ::testing::HasSubstr;

// One second of scenario I with every disturbance: the draws differ.
RunControls one_second() {
  RunControls controls;
  controls.duration = 1.0;
  return controls;
}

const char* const kScenario = THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml";

TEST(ClosedLoop, MetricsAndTheirNames) {
  sim::RunSummary s;
  s.cost = 12.5;
  s.rms_tracking_error = Eigen::Vector3d(0.3, 0.4, 1.2);
  EXPECT_EQ(metric_value(s, Metric::cost), 12.5);
  EXPECT_DOUBLE_EQ(metric_value(s, Metric::rms_error), 1.3);
  sim::RunSummary diverged = s;
  diverged.status = sim::RunStatus::diverged;
  EXPECT_EQ(metric_value(diverged, Metric::cost), std::numeric_limits<double>::infinity());
  EXPECT_EQ(mean_metric({s, s}, Metric::cost), 12.5);
  EXPECT_EQ(mean_metric({s, diverged}, Metric::cost), std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse_metric(metric_name(Metric::rms_error)), Metric::rms_error);
  EXPECT_EQ(parse_metric("cost"), Metric::cost);
  EXPECT_THROW(metric_value(s, Metric::cost_dev), Error);  // a run without J_dev
  s.cost_dev = 3.25;
  EXPECT_EQ(metric_value(s, Metric::cost_dev), 3.25);
  EXPECT_EQ(parse_metric(metric_name(Metric::cost_dev)), Metric::cost_dev);
  EXPECT_THROW(
      {
        try {
          parse_metric("speed");
        } catch (const Error& error) {
          EXPECT_THAT(error.what(), HasSubstr("unknown metric 'speed' (known: cost, rms-error, cost-dev)"));
          throw;
        }
      },
      Error);
}

TEST(ClosedLoop, FliesEachSeedTheSameForAnyNumberOfWorkers) {
  const std::vector<std::uint64_t> seeds{3, 4, 5};
  DrawFlights one(kScenario, one_second(), {}, 3, 1), two(kScenario, one_second(), {}, 3, 2);
  const VectorXd k = Eigen::Vector2d(0.2, 0.7), l = Eigen::Vector2d(3.0, 0.5);
  const std::vector<sim::RunSummary> a = one.fly(k, l, seeds), b = two.fly(k, l, seeds);
  ASSERT_EQ(a.size(), 3u);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    EXPECT_EQ(a[i].status, sim::RunStatus::completed);
    EXPECT_EQ(a[i].settings.seed, seeds[i]);
    EXPECT_EQ(a[i].cost, b[i].cost) << "seed " << seeds[i];
    EXPECT_EQ(a[i].rms_tracking_error, b[i].rms_tracking_error) << "seed " << seeds[i];
  }
  EXPECT_NE(a[0].cost, a[1].cost);  // different draws
  EXPECT_EQ(mean_metric(a, Metric::cost), (a[0].cost + a[1].cost + a[2].cost) / 3.0);
  // The k, l flown are the ones asked for: the paper's k = l = 1 flies otherwise.
  EXPECT_NE(one.fly({}, {}, {3})[0].cost, a[0].cost);
}

TEST(ClosedLoop, SearchKeepsItsBudgetAndReportsWhatItFlew) {
  DrawFlights flights(kScenario, one_second(), {}, 3, 2);
  FitOptions options;
  options.max_local_evaluations = 6;
  const std::vector<std::uint64_t> training{3, 4};
  const FitResult fit = tuning::fit(flights, training, Metric::rms_error, options);
  EXPECT_LE(fit.evaluations, 6);
  EXPECT_LE(fit.residual, fit.start_residual);
  EXPECT_EQ(fit.start_residual, mean_metric(flights.fly({}, {}, training), Metric::rms_error));
  EXPECT_EQ(fit.residual, mean_metric(flights.fly(fit.k, fit.l, training), Metric::rms_error));
  EXPECT_THROW(tuning::fit(flights, {}, Metric::cost, options), Error);
}

}  // namespace
}  // namespace thetad::tuning
