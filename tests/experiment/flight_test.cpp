#include "experiment/flight.hpp"

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/helicopter/state.hpp"
#include "experiment/replay.hpp"
#include "experiment/result_json.hpp"
#include "experiment/run_files.hpp"
#include "experiment/sha256.hpp"
#include "tests/error_message.hpp"
#include "tests/run_seconds.hpp"
#include "tests/scratch_directory.hpp"

namespace thetad {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::seconds;

const std::string kScenario = THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml";

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

RunResult fly(const Flight& flight, const std::string& spec) {
  PreparedController prepared = flight.prepare(parse_controller_spec(spec));
  return flight.fly(prepared);
}

TEST(Flight, RunControlsOverrideTheScenario) {
  RunControls controls = seconds(0.5);
  controls.dt = 5e-4;
  controls.log_every = 10;
  controls.seed = 9;
  controls.ideal = true;
  const Flight flight(kScenario, controls);
  EXPECT_EQ(flight.settings().duration, 0.5);
  EXPECT_EQ(flight.settings().dt, 5e-4);
  EXPECT_EQ(flight.settings().controller_period_steps, 2);
  EXPECT_EQ(flight.settings().controller_period(), 1e-3);
  EXPECT_EQ(flight.settings().seed, 9u);
  EXPECT_FALSE(flight.settings().parameter_uncertainty);
  const RunResult run = fly(flight, "lqr");
  EXPECT_EQ(run.summary.controller_samples, 500);
  EXPECT_EQ(run.log.rows(), 50);
}

// The X-Cell's servos fly every run unless the scenario, `ideal` or the switch says otherwise
// (the paper's two scenarios say off); the summary line says which.
TEST(Flight, ActuatorLimitsAreOnByDefaultAndIdealOrTheSwitchTurnsThemOff) {
  const std::string scenario = THETAD_SOURCE_DIR "/scenarios/hover-to-hover.yaml";
  const Flight by_default(scenario, seconds(0.1));
  EXPECT_TRUE(by_default.settings().actuator_limits.enabled);
  EXPECT_EQ(by_default.disturbances(), "all disturbances (the paper's); actuator limits on");
  EXPECT_FALSE(Flight(kScenario, seconds(0.1)).settings().actuator_limits.enabled);

  RunControls ideal = seconds(0.1);
  ideal.ideal = true;
  EXPECT_FALSE(Flight(scenario, ideal).settings().actuator_limits.enabled);
  EXPECT_EQ(Flight(scenario, ideal).disturbances(), "ideal (no uncertainty, noise, wind or actuator limits)");
  ideal.actuator_limits = true;
  EXPECT_TRUE(Flight(scenario, ideal).settings().actuator_limits.enabled);
  EXPECT_EQ(Flight(scenario, ideal).disturbances(), "no uncertainty, noise or wind; actuator limits on");

  RunControls off = seconds(0.1);
  off.actuator_limits = false;
  const Flight unlimited(scenario, off);
  EXPECT_FALSE(unlimited.settings().actuator_limits.enabled);
  EXPECT_EQ(unlimited.disturbances(), "all disturbances (the paper's); no actuator limits");

  // Some of the paper's and some beyond them (docs/model.md §15): named.
  RunControls some = seconds(0.1);
  some.wind_gust = false;
  some.noise_scale = 0.0;
  some.turbulence_model = thetad::sim::TurbulenceSettings::Model::dryden;
  EXPECT_EQ(Flight(scenario, some).disturbances(),
            "of the paper's disturbances parameter_uncertainty; beyond them turbulence; actuator limits on");
}

TEST(Flight, DisturbanceScalesAndTheInitialOffsetOverrideTheScenario) {
  RunControls controls = seconds(0.2);
  controls.uncertainty_scale = 2.0;
  controls.noise_scale = 0.5;
  controls.gust_scale = 3.0;
  controls.gust_onset = 0.1;
  controls.initial_offset = Eigen::Vector3d(1.0, -0.5, 0.25);
  const Flight flight(kScenario, controls);
  EXPECT_EQ(flight.settings().uncertainty_scale, 2.0);
  EXPECT_EQ(flight.settings().noise.scale, 0.5);
  EXPECT_EQ(flight.settings().wind_gust.amplitude_scale, 3.0);
  EXPECT_EQ(flight.settings().wind_gust.onset, 0.1);
  const Eigen::VectorXd moved = flight.initial_state() - flight.scenario().initial_state;
  EXPECT_EQ(moved.segment<3>(0), Eigen::Vector3d(1.0, -0.5, 0.25));
  EXPECT_TRUE(moved.tail(moved.size() - 3).isZero());
  // The paper's flight and the scaled one differ; the same scaled flight twice is identical.
  controls.timing = false;
  const RunResult scaled = fly(Flight(kScenario, controls), "lqr");
  EXPECT_EQ(fly(Flight(kScenario, controls), "lqr").summary.cost, scaled.summary.cost);
  RunControls paper = seconds(0.2);
  paper.timing = false;
  EXPECT_NE(fly(Flight(kScenario, paper), "lqr").summary.cost, scaled.summary.cost);

  controls.uncertainty_scale = 12.0;
  EXPECT_THROW(Flight(kScenario, controls), Error);
  controls.uncertainty_scale = 1.0;
  controls.noise_scale = -1.0;
  EXPECT_THROW(Flight(kScenario, controls), Error);
  controls.noise_scale = 1.0;
  controls.gust_onset = std::nan("");
  EXPECT_THROW(Flight(kScenario, controls), Error);
}

TEST(Flight, TheInitialAttitudeOffsetTurnsTheStartingState) {
  RunControls controls = seconds(0.2);
  controls.timing = false;
  controls.initial_attitude_offset = Eigen::Vector3d(0.1, -0.05, 0.3);
  const Flight flight(kScenario, controls);
  const Eigen::VectorXd turned = flight.initial_state() - flight.scenario().initial_state;
  EXPECT_EQ(turned.segment<3>(heli::kPhi), Eigen::Vector3d(0.1, -0.05, 0.3));
  EXPECT_TRUE(turned.head<heli::kPhi>().isZero());
  EXPECT_TRUE(turned.tail(turned.size() - heli::kPsi - 1).isZero());
  RunControls level = seconds(0.2);
  level.timing = false;
  EXPECT_NE(fly(flight, "lqr").summary.cost, fly(Flight(kScenario, level), "lqr").summary.cost);
  // Beyond the divergence limit from the start: the run ends at once.
  controls.initial_attitude_offset = Eigen::Vector3d(1.6, 0.0, 0.0);
  const RunResult rolled = fly(Flight(kScenario, controls), "lqr");
  EXPECT_EQ(rolled.summary.status, sim::RunStatus::diverged);
  EXPECT_THAT(rolled.summary.reason, HasSubstr("roll |phi|"));
  controls.initial_attitude_offset = Eigen::Vector3d(0.0, std::nan(""), 0.0);
  EXPECT_THROW(Flight(kScenario, controls), Error);
}

TEST(Flight, TheSpeedScaleFliesTheTrajectoryFasterOverAShorterFlight) {
  RunControls controls;
  controls.speed_scale = 2.0;
  const Flight faster(kScenario, controls);
  const Flight paper(kScenario);
  EXPECT_EQ(faster.settings().duration, paper.settings().duration / 2.0);
  EXPECT_EQ(faster.scenario().trajectory.position(20.0), paper.scenario().trajectory.position(40.0));
  EXPECT_EQ(faster.settings().wind_gust.onset, paper.settings().wind_gust.onset);
  // An explicit duration is the flown time: the first 3.75 s of scenario I's takeoff in 3 s.
  controls.speed_scale = 1.25;
  controls.duration = 3.0;
  controls.timing = false;
  const RunResult run = fly(Flight(kScenario, controls), "lqr");
  EXPECT_EQ(run.summary.controller_samples, 3000);
  EXPECT_EQ(run.summary.status, sim::RunStatus::completed) << run.summary.reason;
  RunControls unscaled = seconds(3.0);
  unscaled.timing = false;
  EXPECT_NE(fly(Flight(kScenario, unscaled), "lqr").summary.cost, run.summary.cost);
  controls.speed_scale = -1.0;
  EXPECT_THROW(Flight(kScenario, controls), Error);
}

TEST(Flight, APlantStepThatDoesNotDivideTheControllerPeriodIsAnErrorNamingBoth) {
  RunControls controls;
  controls.dt = 3e-4;
  try {
    const Flight flight(kScenario, controls);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("dt 0.0003 s does not divide the controller period 0.001 s"));
  }
  controls.dt = 0.002;
  EXPECT_THROW(Flight(kScenario, controls), Error);
  EXPECT_THROW(Flight(kScenario, seconds(86401.0)), Error);
  EXPECT_THROW(Flight(kScenario, seconds(-1.0)), Error);
}

TEST(Flight, SummaryOnlyKeepsNoLogButTheSameSummary) {
  RunControls controls = seconds(0.3);
  controls.timing = false;
  const RunResult logged = fly(Flight(kScenario, controls), "theta-d");
  controls.summary_only = true;
  const RunResult summary_only = fly(Flight(kScenario, controls), "theta-d");
  EXPECT_EQ(logged.log.rows(), 300);
  EXPECT_EQ(summary_only.log.rows(), 0);
  // Every figure of the summary, bit for bit (JSON keeps doubles exactly); only the summary_only setting differs.
  nlohmann::ordered_json with_log = summary_json(logged.summary), without_log = summary_json(summary_only.summary);
  EXPECT_FALSE(with_log.at("settings").at("summary_only"));
  EXPECT_TRUE(without_log.at("settings").at("summary_only"));
  with_log.erase("settings");
  without_log.erase("settings");
  EXPECT_EQ(without_log, with_log);
  EXPECT_GT(without_log.at("cost").get<double>(), 0.0);
}

TEST(Flight, ProvenanceSaysWhatProducedTheRun) {
  const Flight flight(kScenario, seconds(0.1));
  const RunResult run = fly(flight, "paper=theta-d");
  const Provenance& p = run.provenance;
  EXPECT_EQ(p.build.version, "0.1.0");
  EXPECT_FALSE(p.build.build_type.empty());
  EXPECT_FALSE(p.build.compiler.empty());
  EXPECT_THAT(p.build.eigen, HasSubstr("3."));
  EXPECT_THAT(p.build.blas_loaded, HasSubstr("blas"));
  EXPECT_THAT(p.build.lapack_loaded, HasSubstr("lapack"));
  EXPECT_EQ(p.scenario_name, "scenario-1");
  EXPECT_EQ(p.scenario_file, kScenario);
  EXPECT_EQ(p.scenario_sha256, sha256_of_file(kScenario));
  EXPECT_EQ(p.scenario_sha256.size(), 64u);
  EXPECT_EQ(p.model_preset, "resolved");
  EXPECT_THAT(p.model_options, HasSubstr("rotor_speed_model="));
  EXPECT_EQ(p.seed, 1u);
  EXPECT_EQ(p.dt, 1e-3);
  EXPECT_FALSE(p.host.empty());
  EXPECT_EQ(p.start_time.size(), 20u);  // 2026-11-24T22:46:00Z
  EXPECT_EQ(run.spec.label, "paper");

  RunControls no_timing = seconds(0.1);
  no_timing.timing = false;
  const RunResult untimed = fly(Flight(kScenario, no_timing), "theta-d");
  EXPECT_TRUE(untimed.provenance.host.empty());
  EXPECT_TRUE(untimed.provenance.start_time.empty());
  EXPECT_EQ(untimed.wall_time_s, 0.0);
}

TEST(Flight, ShippedScenariosAreFoundByName) {
  EXPECT_EQ(Flight("scenario-2", seconds(0.1)).scenario().name, "scenario-2");
  EXPECT_EQ(Flight("hover-step.yaml", seconds(0.1)).scenario().name, "hover-step");
  try {
    const Flight flight("no-such-scenario");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("scenario 'no-such-scenario': no such file, nor a shipped scenario"));
  }
}

class FlightFiles : public ::testing::Test {
 protected:
  testing::ScratchDirectory scratch_{"thetad_flight_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(FlightFiles, WithoutTimingTwoRunsOfOneSeedGiveByteIdenticalFiles) {
  RunControls controls = seconds(0.2);
  controls.timing = false;
  const RunFiles first = write_run_files(fly(Flight(kScenario, controls), "theta-d"), dir_ / "a");
  const RunFiles second = write_run_files(fly(Flight(kScenario, controls), "theta-d"), dir_ / "b");
  EXPECT_EQ(read(first.csv), read(second.csv));
  EXPECT_EQ(read(first.json), read(second.json));
  EXPECT_THAT(read(first.csv).substr(0, read(first.csv).find('\n')), ::testing::Not(HasSubstr("compute")));
  EXPECT_THAT(read(first.json), ::testing::Not(HasSubstr("start_time")));
  controls.seed = 2;
  const RunFiles other = write_run_files(fly(Flight(kScenario, controls), "theta-d"), dir_ / "c");
  EXPECT_NE(read(first.csv), read(other.csv));
}

TEST_F(FlightFiles, AReplayFliesTheSameRunFromTheResultFileAlone) {
  std::ofstream(dir_ / "tuned.yaml") << "theta-d:\n  k: [0.5, 0.25]\n  l: [2, 3]\n";
  RunControls controls = seconds(0.4);
  controls.seed = 5;
  controls.log_every = 4;
  controls.wind_gust = false;
  const Flight flight(kScenario, controls);
  const RunFiles files =
      write_run_files(fly(flight, "tuned=theta-d:" + (dir_ / "tuned.yaml").string()), dir_ / "out");
  const Replay again = replay(files.json);
  EXPECT_TRUE(again.differences.empty()) << again.differences.front();
  EXPECT_EQ(again.largest_difference, 0.0);  // the same build on the same machine: bit for bit
  EXPECT_EQ(again.result.spec.label, "tuned");
  EXPECT_EQ(again.result.summary.settings.seed, 5u);
  EXPECT_EQ(again.result.summary.settings.log_every, 4);
  EXPECT_FALSE(again.result.summary.settings.wind_gust.enabled);

  // A figure that moved by rounding (another CPU's libm) still agrees, and the replay says by how much.
  nlohmann::ordered_json rounded = nlohmann::ordered_json::parse(read(files.json));
  rounded["cost"] = rounded["cost"].get<double>() * (1.0 + 3e-15);
  std::ofstream(files.json, std::ios::trunc) << rounded.dump(2);
  const Replay near = replay(files.json);
  EXPECT_TRUE(near.differences.empty()) << near.differences.front();
  EXPECT_GT(near.largest_difference, 1e-15);
  EXPECT_LT(near.largest_difference, 1e-14);
  rounded["cost"] = rounded["cost"].get<double>() * (1.0 + 1e-8);
  std::ofstream(files.json, std::ios::trunc) << rounded.dump(2);
  ASSERT_EQ(replay(files.json).differences.size(), 1u);

  // A result edited by hand (or another run's) no longer agrees, and says where.
  std::string text = read(files.json);
  text.insert(text.find("\"cost\": ") + 8, "9");
  std::ofstream(files.json, std::ios::trunc) << text;
  const Replay edited = replay(files.json);
  ASSERT_EQ(edited.differences.size(), 1u);
  EXPECT_THAT(edited.differences[0], HasSubstr("cost"));
}

// A kept campaign log replays too: the initial offsets, the speed scale and the course act outside the
// simulation settings, so the result file records them with the seed.
TEST_F(FlightFiles, AReplayFliesTheSameOffsetAndSpeedScaledRun) {
  RunControls controls = seconds(0.3);
  controls.initial_offset = Eigen::Vector3d(0.5, -0.25, 0.125);
  controls.initial_attitude_offset = Eigen::Vector3d(0.1, -0.05, 0.2);
  controls.speed_scale = 1.5;
  controls.course = 0.75;
  const RunFiles files = write_run_files(fly(Flight(kScenario, controls), "lqr"), dir_);
  EXPECT_THAT(read(files.json), HasSubstr("\"trajectory_speed_scale\": 1.5"));
  EXPECT_THAT(read(files.json), HasSubstr("\"course_rad\": 0.75"));
  const Replay again = replay(files.json);
  EXPECT_TRUE(again.differences.empty()) << again.differences.front();
  EXPECT_EQ(again.result.provenance.initial_offset, (std::array<double, 3>{0.5, -0.25, 0.125}));
  EXPECT_EQ(again.result.provenance.initial_attitude_offset, (std::array<double, 3>{0.1, -0.05, 0.2}));
  EXPECT_EQ(again.result.provenance.speed_scale, 1.5);
  EXPECT_EQ(again.result.provenance.course, 0.75);
}

// The result records the scenario's text: editing (or deleting) the file after the run changes
// nothing of its replay.
TEST_F(FlightFiles, AReplayFliesTheRecordedScenarioWhateverBecameOfItsFile) {
  fs::copy_file(kScenario, dir_ / "scenario.yaml");
  const RunFiles files = write_run_files(fly(Flight((dir_ / "scenario.yaml").string(), seconds(0.1)), "lqr"), dir_);
  std::ofstream(dir_ / "scenario.yaml", std::ios::app) << "# edited\n";
  const Replay edited = replay(files.json);
  EXPECT_TRUE(edited.differences.empty()) << edited.differences.front();
  fs::remove(dir_ / "scenario.yaml");
  EXPECT_TRUE(replay(files.json).differences.empty());
  EXPECT_EQ(nlohmann::json::parse(read(files.json))["format_version"], kRunFormatVersion);
}

// A result of a newer thetad is refused (results of earlier versions: earlier_result_test.cpp).
TEST_F(FlightFiles, NewerResultsAreRefused) {
  const RunFiles files = write_run_files(fly(Flight(kScenario, seconds(0.1)), "lqr"), dir_);
  nlohmann::ordered_json result = nlohmann::ordered_json::parse(read(files.json));
  EXPECT_EQ(result["format_version"], kRunFormatVersion);
  result["format_version"] = kRunFormatVersion + 1;
  std::ofstream(dir_ / "newer.json") << result.dump(2);
  EXPECT_THAT(testing::error_message([&] { replay(dir_ / "newer.json"); }), HasSubstr("written by a newer thetad"));
}

}  // namespace
}  // namespace thetad
