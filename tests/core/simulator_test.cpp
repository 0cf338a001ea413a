#include "core/sim/helicopter_disturbances.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/helicopter/paper_weights.hpp"
#include "core/helicopter/state.hpp"
#include "experiment/result_json.hpp"
#include "experiment/run_files.hpp"
#include "tests/core/hover_trim.hpp"
#include "tests/scratch_directory.hpp"


namespace thetad::sim {
namespace {

using namespace heli;
namespace fs = std::filesystem;

using thetad::testing::hover_trim_input;
using thetad::testing::hover_trim_state;
using thetad::testing::kHoverPoint;

// The log's CSV header: the schema's columns, as the experiment library writes them.
std::string csv_header() {
  std::string header;
  for (const auto& column : helicopter_log_schema()) {
    if (!header.empty()) header += ',';
    header += column.header();
  }
  return header;
}

// A simulator run written by the experiment library's writer under the label `stem`.
thetad::RunFiles write_run(const RunResult& flown, const fs::path& directory, const std::string& stem) {
  thetad::RunResult result;
  result.spec.label = stem;
  result.spec.controller = flown.summary.controller;
  result.summary = flown.summary;
  result.log = flown.log;
  return write_run_files(result, directory);
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The CSV's data rows as numbers, after checking the header against the schema.
std::vector<std::vector<double>> read_csv_rows(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, csv_header());
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) row.push_back(std::stod(field));
    EXPECT_EQ(row.size(), helicopter_log_schema().size());
    rows.push_back(std::move(row));
  }
  return rows;
}

std::size_t column(const std::string& header) {
  const auto& schema = helicopter_log_schema();
  for (std::size_t i = 0; i < schema.size(); ++i)
    if (schema[i].header() == header) return i;
  ADD_FAILURE() << "no column " << header;
  return 0;
}

class SimulatorFiles : public ::testing::Test {
 protected:
  std::vector<std::string> directory_entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(directory_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  thetad::testing::ScratchDirectory scratch_{"thetad_simulator_test"};
  const fs::path directory_ = scratch_.path();
};

SimulationSettings short_paper_run(std::uint64_t seed) {
  SimulationSettings settings = SimulationSettings::paper();
  settings.duration = 0.3;
  settings.measure_compute_time = false;
  settings.seed = seed;
  return settings;
}

TEST(LogSchema, NamesEveryColumnWithItsUnit) {
  const auto& schema = helicopter_log_schema();
  EXPECT_EQ(schema.size(), 1u + 3 + kStateDim + kStateDim + kInputDim + kInputDim + kInputDim + 1 + 3 + 1);
  EXPECT_EQ(schema.front().header(), "t_s");
  EXPECT_EQ(schema.back().header(), "in_flight_step_time_ns");
  for (const auto& c : schema) EXPECT_FALSE(c.unit.empty()) << c.name;
  EXPECT_EQ(csv_header().substr(0, 26), "t_s,x_c_m,y_c_m,z_c_m,x_p_");
  EXPECT_NE(csv_header().find(",phi_rad,"), std::string::npos);
  EXPECT_NE(csv_header().find(",meas_p_rad_per_s,"), std::string::npos);
  EXPECT_NE(csv_header().find(",cmd_T_mr_N,"), std::string::npos);
  EXPECT_NE(csv_header().find(",app_delta_lat_rad,sat_T_mr_flag,"), std::string::npos);
  EXPECT_NE(csv_header().find(",sat_delta_lat_flag,Omega_mr_rad_per_s,wind_N_m_per_s,"), std::string::npos);
}

// Open loop from the printed trim for 1 s, nothing disturbing it: the drift measures how well the
// 5-6 printed digits balance the plant (measured: see the report of this test's output).
TEST(Simulator, OpenLoopHoverFromPrintedTrimStaysNearTrimForOneSecond) {
  SimulationSettings settings = SimulationSettings::ideal();
  settings.duration = 1.0;
  ConstantInput hold(hover_trim_input());
  const RunResult result = simulate(hold, kHoverPoint, hover_trim_state(), settings);
  ASSERT_EQ(result.summary.status, RunStatus::completed) << result.summary.reason;
  const Eigen::VectorXd last = result.log.row(result.log.rows() - 1).segment(4, kStateDim);
  const double drift = (last.head<3>() - hover_trim_state().head<3>()).norm();
  const double attitude_drift = (last.segment<3>(kPhi) - hover_trim_state().segment<3>(kPhi)).norm();
  std::cout << "open-loop hover drift after 1 s: position " << drift << " m, attitude " << attitude_drift
            << " rad, rotor speed " << result.log.row(result.log.rows() - 1)[column("Omega_mr_rad_per_s")]
            << " rad/s\n";
  // Measured: 1.9e-5 m and 7.7e-6 rad (the printed digits' rounding, e.g. 5e-7 rad of delta_ped
  // times 218 rad/s^2 per rad of yaw authority). The bounds leave a factor of ~50.
  EXPECT_LT(drift, 1e-3);
  EXPECT_LT(attitude_drift, 4e-4);
  EXPECT_NEAR(result.log.row(0)[column("Omega_mr_rad_per_s")], 171.966, 0.01);  // docs/model.md §13
}

TEST_F(SimulatorFiles, SameSeedGivesByteIdenticalFilesAndAnotherSeedDiffers) {
  ConstantInput hold(hover_trim_input());
  const auto run = [&](std::uint64_t seed, const char* folder) {
    return write_run(simulate(hold, kHoverPoint, hover_trim_state(), short_paper_run(seed)), directory_ / folder, "run");
  };
  const thetad::RunFiles first = run(42, "a"), second = run(42, "b"), other = run(43, "c");
  EXPECT_EQ(read_file(first.csv), read_file(second.csv));
  EXPECT_EQ(read_file(first.json), read_file(second.json));
  EXPECT_NE(read_file(first.csv), read_file(other.csv));
}

TEST(Simulator, TimingChangesOnlyTheStepTimeColumn) {
  ConstantInput hold(hover_trim_input());
  SimulationSettings timed = short_paper_run(5);
  timed.measure_compute_time = true;
  const RunResult a = simulate(hold, kHoverPoint, hover_trim_state(), short_paper_run(5));
  const RunResult b = simulate(hold, kHoverPoint, hover_trim_state(), timed);
  ASSERT_EQ(a.log.rows(), b.log.rows());
  const auto compute = static_cast<Eigen::Index>(column("in_flight_step_time_ns"));
  for (Eigen::Index i = 0; i < a.log.rows(); ++i) {
    ASSERT_EQ(a.log.row(i).head(compute), b.log.row(i).head(compute)) << "row " << i;
    ASSERT_EQ(a.log.row(i)[compute], 0.0);
    ASSERT_GE(b.log.row(i)[compute], 0.0);
  }
}

void expect_ended_with_finite_rows(const RunResult& result, RunStatus status, const std::string& reason_part,
                                   double t_min, double t_max) {
  EXPECT_EQ(result.summary.status, status);
  EXPECT_NE(result.summary.reason.find(reason_part), std::string::npos) << result.summary.reason;
  EXPECT_GE(result.summary.end_time, t_min);
  EXPECT_LE(result.summary.end_time, t_max);
  EXPECT_EQ(result.log.rows(), result.summary.controller_samples);
  for (Eigen::Index i = 0; i < result.log.rows(); ++i) {
    ASSERT_TRUE(result.log.row(i).allFinite()) << "row " << i;
    ASSERT_LT(result.log.row(i)[0], result.summary.end_time);
  }
}

// With half the hover thrust from 0.5 m it sinks at about g/2 and passes 1 m below the ground
// after about sqrt(2 * 1.5 / 4.9) = 0.78 s (a little later with the fuselage drag).
TEST_F(SimulatorFiles, FallingThroughTheGroundDivergesWithReasonAndFiniteRows) {
  Eigen::VectorXd weak = hover_trim_input();
  weak[kTmr] *= 0.5;
  ConstantInput falling(weak, "falling");
  Eigen::VectorXd x0 = hover_trim_state();
  x0[kZp] = -0.5;
  SimulationSettings settings = SimulationSettings::ideal();
  settings.duration = 3.0;
  const RunResult result = simulate(falling, kHoverPoint, x0, settings);
  expect_ended_with_finite_rows(result, RunStatus::diverged, "ground penetration", 0.75, 1.0);
  const thetad::RunFiles files = write_run(result, directory_, "fall");
  const auto rows = read_csv_rows(files.csv);
  EXPECT_EQ(static_cast<Eigen::Index>(rows.size()), result.log.rows());
  for (const auto& row : rows)
    for (const double v : row) ASSERT_TRUE(std::isfinite(v));
  const auto summary = nlohmann::json::parse(read_file(files.json));
  EXPECT_EQ(summary["status"], "diverged");
  EXPECT_EQ(summary["reason"], result.summary.reason);
}

TEST(Simulator, HugePedalSpinsItUpToTheYawRateLimit) {
  Eigen::VectorXd pedal = hover_trim_input();
  pedal[kPed] = 2.0;
  ConstantInput spin(pedal, "spin");
  SimulationSettings settings = SimulationSettings::ideal();
  settings.duration = 2.0;
  const RunResult result = simulate(spin, kHoverPoint, hover_trim_state(), settings);
  expect_ended_with_finite_rows(result, RunStatus::diverged, "yaw rate |r|", 0.0, 1.0);
}

// A controller that throws (whatever it throws) ends its run as failed, not diverged: the fault is
// the controller's, not the closed loop's.
TEST(Simulator, ControllerErrorEndsTheRunAsFailed) {
  class Failing final : public ControlLaw {
   public:
    std::string name() const override { return "failing"; }
    void reset(const Eigen::VectorXd&, double) override {}
    void control(double t, const Eigen::Ref<const Eigen::VectorXd>&, const Reference&,
                 Eigen::Ref<Eigen::VectorXd> u) override {
      if (t >= 0.05) throw Error("CARE: no stabilizing solution");
      u = hover_trim_input();
    }
  } failing;
  SimulationSettings settings = SimulationSettings::ideal();
  settings.duration = 0.2;
  const RunResult result = simulate(failing, kHoverPoint, hover_trim_state(), settings);
  expect_ended_with_finite_rows(result, RunStatus::failed, "controller failed at t = 0.0500 s: CARE", 0.05, 0.05);
  EXPECT_EQ(result.summary.controller_samples, 50);
}

// A controller's own event counts (the SDRE's Riccati fallbacks, say) reach the summary and its JSON.
TEST(Simulator, SummaryCarriesTheControllerCounters) {
  class Counting final : public ControlLaw {
   public:
    std::string name() const override { return "counting"; }
    void reset(const Eigen::VectorXd&, double) override { samples = 0; }
    void control(double, const Eigen::Ref<const Eigen::VectorXd>&, const Reference&,
                 Eigen::Ref<Eigen::VectorXd> u) override {
      ++samples;
      u = hover_trim_input();
    }
    std::vector<std::pair<std::string, double>> counters() const override { return {{"samples_seen", samples}}; }
    int samples = 0;
  } counting;
  SimulationSettings settings = SimulationSettings::ideal();
  settings.duration = 0.03;
  const RunResult result = simulate(counting, kHoverPoint, hover_trim_state(), settings);
  ASSERT_EQ(result.summary.controller_counters.size(), 1u);
  EXPECT_EQ(result.summary.controller_counters[0].second, 30.0);
  const auto json = nlohmann::json::parse(thetad::summary_json(result.summary).dump());
  EXPECT_EQ(json["controller_counters"]["samples_seen"], 30.0);
}

TEST(Simulator, NonFiniteInitialStateStopsBeforeTheFirstSample) {
  ConstantInput hold(hover_trim_input());
  Eigen::VectorXd x0 = hover_trim_state();
  x0[kU] = std::nan("");
  const RunResult result = simulate(hold, kHoverPoint, x0, SimulationSettings::ideal());
  expect_ended_with_finite_rows(result, RunStatus::diverged, "non-finite state", 0.0, 0.0);
  EXPECT_EQ(result.log.rows(), 0);
}

TEST(Simulator, ControllerSeesReferenceIntegralAndNoisyErrorsAtTheControllerRate) {
  class Recorder final : public ControlLaw {
   public:
    std::string name() const override { return "recorder"; }
    void reset(const Eigen::VectorXd&, double) override {}
    void control(double t, const Eigen::Ref<const Eigen::VectorXd>& y, const Reference& r,
                 Eigen::Ref<Eigen::VectorXd> u) override {
      times.push_back(t);
      integrals.push_back(r.integral);
      own.accumulate(r.position, 0.004);
      measured_integral_error.push_back(y.segment<3>(kXi) - r.integral);
      u = hover_trim_input();
    }
    std::vector<double> times;
    std::vector<Eigen::Vector3d> integrals, measured_integral_error;
    PositionIntegral own;
  } recorder;
  SimulationSettings settings = SimulationSettings::ideal();
  settings.controller_period_steps = 4;
  settings.duration = 0.2;
  const RunResult result = simulate(recorder, kHoverPoint, hover_trim_state(), settings);
  ASSERT_EQ(result.summary.status, RunStatus::completed);
  ASSERT_EQ(recorder.times.size(), 50u);
  EXPECT_DOUBLE_EQ(recorder.times[1], 0.004);
  EXPECT_EQ(recorder.integrals.front(), Eigen::Vector3d::Zero());
  EXPECT_NEAR(recorder.integrals.back().z(), -3.5 * 49 * 0.004, 1e-12);
  // Without noise the measured integral error is the integral of the (tiny) true error.
  EXPECT_LT(recorder.measured_integral_error.back().norm(), 1e-3);
}

TEST_F(SimulatorFiles, SummaryFieldsArePresentAndAgreeWithTheCsv) {
  ConstantInput hold(hover_trim_input(), "hold_trim");
  SimulationSettings settings = SimulationSettings::paper();
  settings.duration = 0.5;
  settings.seed = 77;
  const RunResult result = simulate(hold, kHoverPoint, hover_trim_state(), settings);
  const thetad::RunFiles files = write_run(result, directory_, "summary");
  EXPECT_EQ(directory_entries(), (std::vector<std::string>{"summary.csv", "summary.json"}));

  const auto json = nlohmann::json::parse(read_file(files.json));
  for (const char* key : {"controller", "controller_name", "seed", "status", "reason", "end_time_s", "controller_samples",
                          "model_options", "parameter_factors", "settings", "rms_error_x_m", "rms_error_m",
                          "max_error_z_m", "max_axis_error_m", "rms_command_T_mr_N", "saturated_samples", "cost",
                          "in_flight_step_time_median_us"})
    EXPECT_TRUE(json.contains(key)) << key;
  EXPECT_EQ(json["controller_name"], "hold_trim");
  EXPECT_EQ(json["seed"], 77u);
  EXPECT_EQ(json["status"], "completed");
  EXPECT_EQ(json["reason"], "");
  EXPECT_DOUBLE_EQ(json["end_time_s"].get<double>(), 0.5);
  EXPECT_EQ(json["parameter_factors"].size(), 21u);
  EXPECT_TRUE(json["settings"]["noise"]["measurement"].get<bool>());
  EXPECT_EQ(json["settings"]["noise"]["measurement_on"], "feedback_signal");
  for (const char* key : {"mean", "median", "p99"})
    EXPECT_TRUE(json.contains(std::string("in_flight_step_time_") + key + "_us")) << key;
  EXPECT_GT(json["cost"].get<double>(), 0.0);

  const auto rows = read_csv_rows(files.csv);
  ASSERT_EQ(static_cast<std::int64_t>(rows.size()), json["controller_samples"].get<std::int64_t>());
  Eigen::Vector3d square_sum = Eigen::Vector3d::Zero(), max_error = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, kInputDim, 1> command_square_sum = Eigen::Matrix<double, kInputDim, 1>::Zero();
  for (const auto& row : rows) {
    for (int i = 0; i < 3; ++i) {
      const double error = row[column(helicopter_log_schema()[4 + i].header())] - row[1 + i];
      square_sum[i] += error * error;
      max_error[i] = std::max(max_error[i], std::abs(error));
    }
    for (int j = 0; j < kInputDim; ++j) command_square_sum[j] += std::pow(row[column("cmd_T_mr_N") + j], 2);
    EXPECT_EQ(row[column("cmd_T_mr_N")], hover_trim_input()[kTmr]);
  }
  const double n = static_cast<double>(rows.size());
  for (int i = 0; i < 3; ++i) {
    const std::string axis = std::string(1, "xyz"[i]);
    EXPECT_NEAR(json["rms_error_" + axis + "_m"].get<double>(), std::sqrt(square_sum[i] / n), 1e-12);
    EXPECT_EQ(json["max_error_" + axis + "_m"].get<double>(), max_error[i]);
  }
  EXPECT_NEAR(json["rms_error_m"].get<double>(), std::sqrt(square_sum.sum() / n), 1e-12);
  EXPECT_EQ(json["max_axis_error_m"].get<double>(), max_error.maxCoeff());
  EXPECT_NEAR(json["rms_command_T_mr_N"].get<double>(), std::sqrt(command_square_sum[0] / n), 1e-9);

  // J of Eq. 32 from the logged true state and command: V_track of Eq. 36 with the true position
  // error and its integral (rectangle rule, before the sample's own error is added).
  const Eigen::VectorXd q = paper_state_weights();
  const Eigen::VectorXd r = paper_input_weights();
  Eigen::Vector3d error_integral = Eigen::Vector3d::Zero();
  double cost = 0.0;
  for (const auto& row : rows) {
    Eigen::VectorXd v(kStateDim);
    for (int i = 0; i < kStateDim; ++i) v[i] = row[column(helicopter_log_schema()[4 + i].header())];
    const Eigen::Vector3d error = v.segment<3>(kXp) - Eigen::Vector3d(row[1], row[2], row[3]);
    v.segment<3>(kXp) = error;
    v.segment<3>(kXi) = error_integral;
    v[kS] = 1.0;
    Eigen::VectorXd u(kInputDim);
    for (int j = 0; j < kInputDim; ++j) u[j] = row[column("cmd_T_mr_N") + j];
    cost += 0.5 * (v.cwiseAbs2().dot(q) + u.cwiseAbs2().dot(r)) * settings.controller_period();
    error_integral += error * settings.controller_period();
  }
  EXPECT_NEAR(json["cost"].get<double>(), cost, 1e-9 * cost);
}

TEST(Simulator, LogsEveryKthControllerSample) {
  ConstantInput hold(hover_trim_input());
  SimulationSettings settings = SimulationSettings::ideal();
  settings.duration = 0.1;
  settings.log_every = 7;
  const RunResult result = simulate(hold, kHoverPoint, hover_trim_state(), settings);
  EXPECT_EQ(result.summary.controller_samples, 100);
  EXPECT_EQ(result.log.rows(), 15);  // samples 0, 7, ..., 98
  EXPECT_DOUBLE_EQ(result.log.row(1)[0], 0.007);
}

TEST_F(SimulatorFiles, FailedWriteLeavesNoFile) {
  ConstantInput hold(hover_trim_input());
  SimulationSettings settings = SimulationSettings::ideal();
  settings.duration = 0.05;
  const RunResult result = simulate(hold, kHoverPoint, hover_trim_state(), settings);

  std::ofstream(directory_ / "file") << "not a folder";
  EXPECT_THROW(write_run(result, directory_ / "file" / "below", "run"), Error);
  EXPECT_EQ(directory_entries(), std::vector<std::string>{"file"});
  fs::remove(directory_ / "file");

  // The JSON's final name is taken by a non-empty directory: the rename of the JSON (the last one)
  // fails after the CSV's, and the CSV must go too.
  fs::create_directories(directory_ / "run.json" / "occupied");
  EXPECT_THROW(write_run(result, directory_, "run"), Error);
  EXPECT_EQ(directory_entries(), std::vector<std::string>{"run.json"});
  EXPECT_TRUE(fs::is_directory(directory_ / "run.json"));
}

TEST(Simulator, RejectsInvalidSettings) {
  ConstantInput hold(hover_trim_input());
  SimulationSettings settings = SimulationSettings::ideal();
  settings.controller_period_steps = 0;
  EXPECT_THROW(simulate(hold, kHoverPoint, hover_trim_state(), settings), Error);
  EXPECT_THROW(simulate(hold, kHoverPoint, Eigen::VectorXd::Zero(17), SimulationSettings::ideal()), Error);
}

}  // namespace
}  // namespace thetad::sim
