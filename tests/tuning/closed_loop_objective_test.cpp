// The closed-loop objective: θ–D flights over seeded draws through the experiment library, the
// same for any number of workers, scored by the mean cost or RMS error, a diverged draw by +∞;
// and its search within an evaluation budget, over θ–D's series or any controller's weights.
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/helicopter/helicopter.hpp"
#include "core/helicopter/state.hpp"
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
  EXPECT_STREQ(metric_name(Metric::rms_error), "rms_error_m");
  EXPECT_EQ(parse_metric("rms-error"), Metric::rms_error);  // its name before docs/glossary.md
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
          EXPECT_THAT(error.what(), HasSubstr("unknown metric 'speed' (known: cost, rms_error_m, cost_dev)"));
          throw;
        }
      },
      Error);
}

TEST(ClosedLoop, FliesEachSeedTheSameForAnyNumberOfWorkers) {
  const std::vector<std::uint64_t> seeds{3, 4, 5};
  const Parameterization series = series_parameters({}, 3, FitOptions{});
  DrawFlights one(kScenario, one_second(), series, 1), two(kScenario, one_second(), series, 2);
  const VectorXd x = Eigen::Vector4d(0.2, 0.7, 3.0, 0.5);  // k, then l
  const std::vector<sim::RunSummary> a = one.fly(x, seeds), b = two.fly(x, seeds);
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
  EXPECT_NE(one.fly(series.given, {3})[0].cost, a[0].cost);
}

// A front end stops the draws through the observer of the calling thread (Python's Ctrl-C): its
// exception ends fly() and the other worker's flight stops too, long before an hour is flown.
TEST(ClosedLoop, AnObserverStopsEveryWorker) {
  struct Stop {};
  RunControls hour;
  hour.duration = 3600.0;
  const Parameterization series = series_parameters({}, 3, FitOptions{});
  DrawFlights flights(kScenario, hour, series, 2);
  double seen = 0.0;
  flights.set_observer([&](double t) {
    seen = t;
    if (t >= 0.5) throw Stop{};
  });
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(flights.fly(series.given, {1, 2, 3}), Stop);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
  EXPECT_GE(seen, 0.5);
  EXPECT_LT(seen, 1.0);
}

TEST(ClosedLoop, SearchKeepsItsBudgetAndReportsWhatItFlew) {
  FitOptions options;
  options.max_local_evaluations = 6;
  DrawFlights flights(kScenario, one_second(), series_parameters({}, 3, options), 2);
  const std::vector<std::uint64_t> training{3, 4};
  const FitResult fit = tuning::fit(flights, training, Metric::rms_error, options);
  EXPECT_LE(fit.evaluations, 6);
  EXPECT_LE(fit.residual, fit.start_residual);
  EXPECT_EQ(fit.start_residual, mean_metric(flights.fly(flights.parameters().given, training), Metric::rms_error));
  EXPECT_EQ(fit.residual, mean_metric(flights.fly(fit.x, training), Metric::rms_error));
  EXPECT_EQ(fit.x.head(2), fit.k);
  EXPECT_EQ(fit.x.tail(2), fit.l);
  EXPECT_THROW(tuning::fit(flights, {}, Metric::cost, options), Error);
}

// Any controller's weights, with the same objective and budget: the hover LQR's Q and R scaled by
// groups, the positions' group the reference.
TEST(ClosedLoop, TunesAnyControllersWeightsWithTheSameBudget) {
  const heli::Helicopter plant;
  const Parameterization weights = weight_parameters("lqr", {}, plant, 1.5);
  // Velocities, angles (attitude and flapping), rates and integrals; five inputs.
  ASSERT_EQ(weights.names.size(), 9u);
  EXPECT_EQ(weights.names.front(), "log10 Q[m_per_s]");
  EXPECT_EQ(weights.names.back(), "log10 R[delta_lat]");
  EXPECT_EQ(weights.box.lower, VectorXd::Constant(9, -1.5));
  EXPECT_EQ(weights.box.start, VectorXd::Zero(9));
  // The start is the controller as given: the plant's design weights.
  const DesignDefaults design = plant.design_defaults();
  const auto diagonal = [](const YAML::Node& node) {
    const auto values = node.as<std::vector<double>>();
    return VectorXd(Eigen::Map<const VectorXd>(values.data(), static_cast<Eigen::Index>(values.size())));
  };
  EXPECT_EQ(diagonal(weights.given.settings["Q"]), design.state_weights);
  VectorXd x = VectorXd::Zero(9);
  x[0] = 1.0;   // velocities × 10
  x[8] = -0.5;  // δ_lat's R / √10
  const ControllerSpec moved = weights.spec(x, "moved");
  const VectorXd Q = diagonal(moved.settings["Q"]), R = diagonal(moved.settings["R"]);
  EXPECT_EQ(Q.head<3>(), design.state_weights.head<3>());  // positions: the reference group
  EXPECT_DOUBLE_EQ(Q[heli::kU], 10.0 * design.state_weights[heli::kU]);
  EXPECT_EQ(Q[heli::kPhi], design.state_weights[heli::kPhi]);
  EXPECT_DOUBLE_EQ(R[4], design.input_weights[4] / std::sqrt(10.0));
  EXPECT_EQ(R.head<4>(), design.input_weights.head<4>());

  FitOptions options;
  options.algorithm = "LN_COBYLA";
  options.max_local_evaluations = 4;
  DrawFlights flights(kScenario, one_second(), weights, 2);
  const std::vector<std::uint64_t> training{3};
  const FitResult fit = tuning::fit(flights, training, Metric::cost_dev, options);
  EXPECT_LE(fit.evaluations, 4);
  EXPECT_LE(fit.residual, fit.start_residual);
  EXPECT_EQ(fit.start_residual, mean_metric(flights.fly(weights.given, training), Metric::cost_dev));
  EXPECT_EQ(fit.residual, mean_metric(flights.fly(fit.x, training), Metric::cost_dev));
  EXPECT_EQ(fit.k.size(), 0);
  EXPECT_THROW(weight_parameters("lqr", {}, plant, 0.0), Error);
}

}  // namespace
}  // namespace thetad::tuning
