// The k_i, l_i fit (docs/model.md §8.1): recovery of known parameters, determinism over threads, a real
// SDRE record, and clear errors for bad input.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "controllers/registry.hpp"
#include "controllers/sdre.hpp"
#include "core/error.hpp"
#include "scenarios/scenario.hpp"
#include "tests/scratch_directory.hpp"
#include "tests/tuning/helicopter_theta_d.hpp"
#include "tuning/record.hpp"
#include "tuning/sigma_fit.hpp"

namespace thetad::tuning {
namespace {

using Eigen::VectorXd;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

// The record of testing::theta_d_targets: σ_max of the θ–D's own value matrices at known k, l.
TuningRecord sigma_targets(const testing::HelicopterThetaD& heli, const VectorXd& k, const VectorXd& l) {
  return testing::theta_d_targets(heli, k, l).record;
}

TEST(SigmaFit, RecoversKnownParameters) {
  const testing::HelicopterThetaD heli;
  const VectorXd k_true = Eigen::Vector2d(0.6, 1.2), l_true = Eigen::Vector2d(1.8, 0.5);
  const SigmaMatch match(heli.make(3), sigma_targets(heli, k_true, l_true), 2);
  // The targets are exact: scale does not matter.
  const FitResult fit = tuning::fit(match, Weighting::relative, FitOptions{});
  EXPECT_LT(fit.residual, 1e-20);
  EXPECT_LT(fit.residual, fit.start_residual);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(fit.k[i], k_true[i], 1e-4 * k_true[i]) << "k" << i + 1;
    EXPECT_NEAR(fit.l[i], l_true[i], 1e-4 * l_true[i]) << "l" << i + 1;
  }
  RecordProperty("evaluations", fit.evaluations);
}

TEST(SigmaFit, ResidualIsBitIdenticalForAnyThreadCount) {
  const testing::HelicopterThetaD heli;
  const TuningRecord record = sigma_targets(heli, Eigen::Vector2d(0.6, 1.2), Eigen::Vector2d(1.8, 0.5));
  const VectorXd k = Eigen::Vector2d(0.9, 0.3), l = Eigen::Vector2d(4.0, 0.2);
  const double one = SigmaMatch(heli.make(3), record, 1).residual(k, l, Weighting::absolute);
  for (int threads : {2, 3, 5}) EXPECT_EQ(SigmaMatch(heli.make(3), record, threads).residual(k, l, Weighting::absolute), one);
}

// A few seconds of scenario I flown by the SDRE: the fit must not make the match worse.
TEST(SigmaFit, TunedResidualOnARealRecordIsNoWorse) {
  const testing::HelicopterThetaD heli;
  RunControls three_seconds;
  three_seconds.duration = 3.0;
  three_seconds.summary_only = true;
  const Flight flight(THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml", three_seconds);
  const PreparedController sdre = flight.prepare({"sdre", "sdre", {}, {}, {}});
  const TuningRecord record = record_sdre_flight(flight, dynamic_cast<const SdreController&>(*sdre.controller), 10, 2);
  ASSERT_EQ(record.size(), 300);
  const SigmaMatch match(heli.make(3), record, 2);
  const FitResult fit = tuning::fit(match, Weighting::absolute, FitOptions{});
  EXPECT_LE(fit.residual, fit.start_residual);
  const VectorXd ones = VectorXd::Ones(2);
  EXPECT_EQ(fit.start_residual, match.residual(ones, ones, Weighting::absolute));
  EXPECT_EQ(fit.residual, match.residual(fit.k, fit.l, Weighting::absolute));
  RecordProperty("residual_default", std::to_string(fit.start_residual));
  RecordProperty("residual_tuned", std::to_string(fit.residual));
}

// ---- files and bad input ------------------------------------------------------------------------

class RecordFile : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  // The error message of reading `text` as a 2-state, 1-input record.
  std::string read_error(const std::string& text) const {
    try {
      read_record(write("bad.csv", text), 2, 1);
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  }

  const std::string head_ = "# thetad tuning record v1: SDRE flight, sigma_max of P_SDRE at each kept sample\n"
                            "# scenario: tiny\nt_s,x_0,x_1,u_0,sigma_max_P\n";
  thetad::testing::ScratchDirectory scratch_{"thetad_tuning_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(RecordFile, RoundTripIsExact) {
  TuningRecord record;
  record.scenario = "tiny";
  record.time = {0.0, 0.01};
  record.states = (Eigen::MatrixXd(2, 2) << 0.1, 1.0 / 3.0, -2e-17, 4.5).finished();
  record.inputs = (Eigen::MatrixXd(1, 2) << 78.9, -0.0).finished();
  record.sigma_sdre = Eigen::Vector2d(3.25e6, 1.0 / 7.0);
  write_record(dir_ / "r.csv", record);
  const TuningRecord back = read_record(dir_ / "r.csv", 2, 1);
  EXPECT_EQ(back.scenario, "tiny");
  EXPECT_EQ(back.time, record.time);
  EXPECT_EQ(back.states, record.states);
  EXPECT_EQ(back.inputs, record.inputs);
  EXPECT_EQ(back.sigma_sdre, record.sigma_sdre);
}

TEST_F(RecordFile, BadFilesGiveClearErrors) {
  EXPECT_THROW(read_record(dir_ / "missing.csv", 2, 1), Error);
  try {
    read_record(dir_ / "missing.csv", 2, 1);
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("tuning record: cannot read " + (dir_ / "missing.csv").string()));
  }
  EXPECT_THAT(read_error("t,x\n"), HasSubstr(":1: not a thetad tuning record"));
  EXPECT_THAT(read_error(head_.substr(0, head_.rfind("t_s")) + "t_s,x_0,u_0,sigma_max_P\n0,1,2,3\n"),
              HasSubstr(":3: wrong columns for a plant with 2 states and 1 inputs"));
  EXPECT_THAT(read_error(head_ + "0,1,2,3,4\n0.01,1,nan,3,4\n"), HasSubstr("bad.csv:5: column 3: not finite"));
  EXPECT_THAT(read_error(head_ + "0,1,2,3\n"), HasSubstr(":4: only 4 of 5 columns"));
  EXPECT_THAT(read_error(head_ + "0,1,2,3,4,5\n"), HasSubstr(":4: more than 5 columns"));
  EXPECT_THAT(read_error(head_ + "0,1,x,3,4\n"), HasSubstr(":4: column 3: not a number"));
  EXPECT_THAT(read_error(head_ + "0,1,2,3,4\n0,1,2,3,4\n"), HasSubstr(":5: time does not increase"));
  EXPECT_THAT(read_error(head_), HasSubstr("no samples"));
}

}  // namespace
}  // namespace thetad::tuning
