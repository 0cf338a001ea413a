// The per-entry fit of ΣT_i to P: its scaling (each entry by itself, entries near zero by the
// floor), recovery of known k, l, determinism over threads, and clear errors.
#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tests/tuning/helicopter_theta_d.hpp"
#include "tuning/entry_fit.hpp"
#include "tuning/packed_series.hpp"

namespace thetad::tuning {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using ::testing::HasSubstr;

const VectorXd k_true = Eigen::Vector2d(0.6, 1.2), l_true = Eigen::Vector2d(1.8, 0.5);

TEST(EntryFit, RecoversKnownParameters) {
  const testing::HelicopterThetaD heli;
  const testing::ThetaDTargets targets = testing::theta_d_targets(heli, k_true, l_true);
  const EntryMatch match(heli.make(3), targets.record, targets.packed, 1e-3, 2);
  const FitResult fit = tuning::fit(match, FitOptions{});
  EXPECT_LT(match.residual(k_true, l_true), 1e-18);
  EXPECT_LT(fit.residual, 1e-16);
  EXPECT_LT(fit.residual, fit.start_residual);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(fit.k[i], k_true[i], 1e-4 * k_true[i]) << "k" << i + 1;
    EXPECT_NEAR(fit.l[i], l_true[i], 1e-4 * l_true[i]) << "l" << i + 1;
  }
  RecordProperty("evaluations", fit.evaluations);
}

// One sample whose target differs from ΣT_i at k = l = 1 in two entries: a diagonal one off by
// 10 % of the target, and an off-diagonal one set to zero, scaled by the floor.
TEST(EntryFit, ScalesEachEntryByItselfAndEntriesNearZeroByTheFloor) {
  const testing::HelicopterThetaD heli;
  const VectorXd ones = VectorXd::Ones(2);
  testing::ThetaDTargets targets = testing::theta_d_targets(heli, ones, ones);
  targets.record.time.resize(1);
  targets.record.states.conservativeResize(Eigen::NoChange, 1);
  targets.record.inputs.conservativeResize(Eigen::NoChange, 1);
  const Eigen::Index n = heli.model.state_dim();
  MatrixXd P(n, n);
  unpack_lower(targets.packed.col(0).data(), P);
  const MatrixXd S = P;  // ΣT_i at k = l = 1, t = 0
  const Eigen::Index r = 4, c = 1;  // a nonzero coupling
  ASSERT_NE(S(r, c), 0.0);
  P(2, 2) = 1.1 * S(2, 2);
  P(r, c) = 0.0;
  const double floor = 0.01;
  MatrixXd changed(targets.packed.rows(), 1);
  pack_lower(P, changed.data());
  const EntryMatch match(heli.make(3), targets.record, changed, floor, 1);
  const double diagonal = 0.1 / 1.1, coupling = S(r, c) / (floor * std::sqrt(S(r, r) * S(c, c)));
  const double expected = diagonal * diagonal + 2.0 * coupling * coupling;  // both triangles of the coupling
  EXPECT_NEAR(match.residual(ones, ones), expected, 1e-9 * expected);
  EXPECT_NEAR(match.rms_relative_error(ones, ones), std::sqrt(expected / static_cast<double>(n * n)), 1e-9);
}

TEST(EntryFit, ResidualIsBitIdenticalForAnyThreadCount) {
  const testing::HelicopterThetaD heli;
  const testing::ThetaDTargets targets = testing::theta_d_targets(heli, k_true, l_true);
  const VectorXd k = Eigen::Vector2d(0.9, 0.3), l = Eigen::Vector2d(4.0, 0.2);
  const double one = EntryMatch(heli.make(3), targets.record, targets.packed, 1e-3, 1).residual(k, l);
  for (int threads : {2, 3, 5})
    EXPECT_EQ(EntryMatch(heli.make(3), targets.record, targets.packed, 1e-3, threads).residual(k, l), one);
}

TEST(EntryFit, BadInputGivesClearErrors) {
  const testing::HelicopterThetaD heli;
  const testing::ThetaDTargets targets = testing::theta_d_targets(heli, k_true, l_true);
  const auto error_of = [&](const MatrixXd& packed, double floor) -> std::string {
    try {
      EntryMatch(heli.make(3), targets.record, packed, floor, 1);
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  };
  EXPECT_THAT(error_of(targets.packed, 0.0), HasSubstr("the entry scale floor must lie in (0, 1], got 0"));
  EXPECT_THAT(error_of(targets.packed.leftCols(3), 1e-3), HasSubstr("3 target matrices of 171 packed entries for 200 samples"));
  MatrixXd zero_diagonal = targets.packed;
  zero_diagonal(0, 7) = 0.0;  // P(0, 0) of sample 7
  EXPECT_THAT(error_of(zero_diagonal, 1e-3), HasSubstr("P at sample 7 has P(0, 0) = 0"));
}

}  // namespace
}  // namespace thetad::tuning
