// Certificates along a flight (docs/model.md §8.4): their log columns, the summary's worst values
// and times, the result JSON and its replay; the flight loop's check of a law's values.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/sim/helicopter_disturbances.hpp"
#include "experiment/flight.hpp"
#include "experiment/json_file.hpp"
#include "experiment/replay.hpp"
#include "experiment/result_json.hpp"
#include "experiment/run_files.hpp"
#include "scenarios/scenario.hpp"
#include "tests/scratch_directory.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;

const std::string kScenario = THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml";

RunResult fly(const std::string& controller, const std::string& settings, double duration, int log_every = 1) {
  RunControls controls;
  controls.duration = duration;
  controls.log_every = log_every;
  controls.timing = false;
  const Flight flight(kScenario, controls);
  PreparedController prepared = flight.prepare({controller, controller, YAML::Load(settings), "", {}});
  return flight.fly(prepared);
}

std::vector<std::string> headers(const sim::RunLog& log) {
  std::vector<std::string> names;
  for (const auto& column : log.columns) names.push_back(column.header());
  return names;
}

Eigen::Index column(const sim::RunLog& log, const std::string& header) {
  const std::vector<std::string> names = headers(log);
  return std::find(names.begin(), names.end(), header) - names.begin();
}

TEST(CertificatesFlight, AreAbsentWhenOff) {
  const RunResult run = fly("sdre", "{}", 0.05);
  EXPECT_EQ(run.summary.status, sim::RunStatus::completed);
  EXPECT_THAT(headers(run.log), ::testing::Not(::testing::Contains("condition_estimate")));
  EXPECT_EQ(run.log.columns.size(), sim::helicopter_log_schema().size());
  EXPECT_TRUE(run.summary.certificates.empty());
  EXPECT_FALSE(summary_json(run.summary).contains("certificates"));
}

// Logged at every sample, the worst values and their times are those of the log's columns.
TEST(CertificatesFlight, SummaryHoldsTheWorstLoggedValuesAndTheirTimes) {
  const std::vector<std::pair<std::string, std::size_t>> cases{{"sdre", 3}, {"theta-d", 1}};
  for (const auto& [controller, count] : cases) {
    const RunResult run = fly(controller, "{certificates: on}", 0.3);
    ASSERT_EQ(run.summary.status, sim::RunStatus::completed) << run.summary.reason;
    ASSERT_EQ(run.summary.certificates.size(), count);
    // After the disturbances' columns, before the step time.
    EXPECT_EQ(run.log.columns.size(), sim::helicopter_log_schema().size() + count);
    EXPECT_EQ(run.log.columns.back().header(), sim::step_time_column().header());
    for (const CertificateWorst& worst : run.summary.certificates) {
      const Eigen::Index c = column(run.log, worst.certificate.column.header());
      ASSERT_LT(c, static_cast<Eigen::Index>(run.log.columns.size()));
      const bool largest = worst.certificate.worst == ControllerColumn::Worst::largest;
      Eigen::Index at = 0;
      for (Eigen::Index row = 1; row < run.log.rows(); ++row) {
        const double value = run.log.row(row)[c], best = run.log.row(at)[c];
        if (largest ? value > best : value < best) at = row;
      }
      EXPECT_EQ(worst.value, run.log.row(at)[c]) << worst.certificate.column.name;
      EXPECT_EQ(worst.t, run.log.row(at)[0]) << worst.certificate.column.name;
      EXPECT_TRUE(std::isfinite(worst.value)) << worst.certificate.column.name;
    }
    const auto json = summary_json(run.summary).at("certificates");
    const CertificateWorst& first = run.summary.certificates.front();
    EXPECT_EQ(json.at(first.certificate.column.header()).at("value").get<double>(), first.value);
    EXPECT_EQ(json.at(first.certificate.column.header()).at("t_s").get<double>(), first.t);
  }
}

// With a thinned log the summary still sees every sample.
TEST(CertificatesFlight, SummaryCoversTheSamplesTheLogLeavesOut) {
  const RunResult every = fly("theta-d", "{certificates: on}", 0.3, 1);
  const RunResult thinned = fly("theta-d", "{certificates: on}", 0.3, 7);
  EXPECT_EQ(every.summary.certificates.front().value, thinned.summary.certificates.front().value);
  EXPECT_EQ(every.summary.certificates.front().t, thinned.summary.certificates.front().t);
}

TEST(CertificatesFlight, AResultWithCertificatesReplays) {
  const testing::ScratchDirectory dir("certificates_flight_test");
  const RunFiles files = write_run_files(fly("sdre", "{certificates: on, mode: cold}", 0.1, 10), dir.path());
  const auto recorded = read_json_file(files.json);
  ASSERT_TRUE(recorded.contains("certificates"));
  EXPECT_TRUE(recorded.at("certificates").contains("stabilizability_margin"));
  EXPECT_THAT(recorded.at("log").at("columns").dump(), HasSubstr("forward_error_estimate"));
  const Replay again = replay(files.json);
  EXPECT_TRUE(again.differences.empty()) << again.differences.front();
}

// `law` on the nominal helicopter for 10 ms of the scenario, ideal.
sim::RunResult fly_ten_samples(ControlLaw& law) {
  const Scenario scenario = load_scenario(kScenario);
  sim::SimulationSettings settings = sim::SimulationSettings::ideal();
  settings.duration = 0.01;
  return sim::simulate(law, scenario.trajectory, scenario.initial_state, settings, heli::Parameters::nominal(),
                       scenario.model_options);
}

// A law whose values do not match its columns ends its run as failed, not with a shifted log.
class Miscounting final : public ControlLaw {
 public:
  std::string name() const override { return "miscounting"; }
  void reset(const Eigen::VectorXd&, double) override {}
  void control(double, const Eigen::Ref<const Eigen::VectorXd>&, const Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    u.setZero();
    u[0] = 53.0;
  }
  std::vector<ControllerColumn> log_columns() const override {
    return {{{"a", ""}, ControllerColumn::Worst::largest}, {{"b", ""}, ControllerColumn::Worst::smallest}};
  }
  void log_values(std::vector<double>& row) const override { row.push_back(1.0); }
};

TEST(CertificatesFlight, ALawGivingTooFewValuesFails) {
  Miscounting law;
  const sim::RunResult run = fly_ten_samples(law);
  EXPECT_EQ(run.summary.status, sim::RunStatus::failed);
  EXPECT_THAT(run.summary.reason, HasSubstr("log_values gave 1 values for 2 log columns"));
}

// A law's plain columns are logged and not summarized; the certificates among them are, each by its
// own values. The plain column comes first and is larger, so that a summary reading the wrong
// column would say so.
class PlainAndCertificate final : public ControlLaw {
 public:
  std::string name() const override { return "plain-and-certificate"; }
  void reset(const Eigen::VectorXd&, double) override { steps_ = 0; }
  void control(double, const Eigen::Ref<const Eigen::VectorXd>&, const Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    u.setZero();
    u[0] = 53.0;
    ++steps_;
  }
  std::vector<ControllerColumn> log_columns() const override {
    return {{{"plain", "m"}}, {{"certificate", ""}, ControllerColumn::Worst::smallest}};
  }
  void log_values(std::vector<double>& row) const override {
    row.push_back(1000.0 + steps_);
    row.push_back(10.0 - steps_);
  }

 private:
  int steps_ = 0;
};

TEST(CertificatesFlight, ALawsPlainColumnsAreLoggedAndOnlyItsCertificatesSummarized) {
  PlainAndCertificate law;
  const sim::RunResult run = fly_ten_samples(law);
  ASSERT_EQ(run.summary.status, sim::RunStatus::completed) << run.summary.reason;
  ASSERT_EQ(run.summary.certificates.size(), 1u);
  EXPECT_EQ(run.summary.certificates[0].certificate.column.name, "certificate");
  EXPECT_EQ(run.summary.certificates[0].value, 0.0);  // 10 samples: 9, 8, ..., 0
  EXPECT_DOUBLE_EQ(run.summary.certificates[0].t, 0.009);
  const Eigen::Index plain = column(run.log, "plain_m");
  ASSERT_LT(plain, static_cast<Eigen::Index>(run.log.columns.size()));
  EXPECT_EQ(run.log.row(run.log.rows() - 1)[plain], 1010.0);
  EXPECT_EQ(run.log.columns.back().header(), sim::step_time_column().header());
}

}  // namespace
}  // namespace thetad
