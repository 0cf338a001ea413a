// The held-out validation: its seeds never repeat a training seed, it flies exactly those seeds,
// and the paired comparison of a controller with itself is zero.
#include <algorithm>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tuning/held_out.hpp"

namespace thetad::tuning {
namespace {

using ::testing::HasSubstr;

TEST(DrawSeeds, HeldOutSeedsAreDisjointFromTrainingSeeds) {
  const DrawSeeds seeds = draw_seeds(7, 5, 12, 10);  // the command's default: right after training
  EXPECT_EQ(seeds.training, (std::vector<std::uint64_t>{7, 8, 9, 10, 11}));
  ASSERT_EQ(seeds.held_out.size(), 10u);
  EXPECT_EQ(seeds.held_out.front(), 12u);
  for (std::uint64_t seed : seeds.held_out)
    EXPECT_EQ(std::count(seeds.training.begin(), seeds.training.end(), seed), 0) << seed;
  EXPECT_EQ(draw_seeds(7, 5, 100, 3).held_out, (std::vector<std::uint64_t>{100, 101, 102}));
  EXPECT_EQ(draw_seeds(7, 5, 1, 6).held_out.back(), 6u);  // ends just before the training seeds
}

TEST(DrawSeeds, OverlapIsRefusedNamingASharedSeed) {
  try {
    draw_seeds(7, 5, 3, 6);  // 3 … 8 meets 7 … 11
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("must not repeat a training draw, and seed 7 is in both"));
  }
  EXPECT_THROW(draw_seeds(7, 5, 11, 1), Error);
  EXPECT_THROW(draw_seeds(7, -1, 20, 1), Error);
}

TEST(HeldOutValidation, FliesTheHeldOutSeedsAndComparesPairs) {
  RunControls controls;
  controls.duration = 1.0;
  DrawFlights flights(THETAD_SOURCE_DIR "/scenarios/scenario-1.yaml", controls,
                      series_parameters({}, 3, FitOptions{}), 2);
  const std::vector<std::uint64_t> seeds{21, 22, 23};
  // Tuned = default (the paper's k = l = 1): every paired difference is zero.
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(4);
  const HeldOutValidation same = validate_held_out(flights, ones, seeds, 1, 500);
  EXPECT_EQ(same.scenario, "scenario-1");
  EXPECT_EQ(same.pairs(), 3);
  EXPECT_EQ(same.default_not_completed() + same.tuned_not_completed(), 0);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    EXPECT_EQ(same.default_runs[i].settings.seed, seeds[i]);
    EXPECT_EQ(same.tuned_runs[i].settings.seed, seeds[i]);
  }
  ASSERT_TRUE(same.cost_dev);
  for (const PairedComparison* c : {&same.cost, &same.rms_error, &*same.cost_dev}) {
    EXPECT_EQ(c->default_median, c->tuned_median);
    EXPECT_EQ(c->difference.median, 0.0);
    EXPECT_EQ(c->difference.low, 0.0);
    EXPECT_EQ(c->difference.high, 0.0);
  }
  // Another k, l: the differences are the per-seed differences of what was flown.
  const HeldOutValidation other = validate_held_out(flights, Eigen::Vector4d(0.0, 0.0, 1.0, 1.0), seeds, 1, 500);
  std::vector<double> differences;
  for (std::size_t i = 0; i < seeds.size(); ++i) differences.push_back(other.tuned_runs[i].cost - other.default_runs[i].cost);
  EXPECT_EQ(other.cost.difference.median, linear_quantile(differences, 0.5));
  EXPECT_NE(other.cost.difference.median, 0.0);
  EXPECT_THROW(validate_held_out(flights, ones, {}, 1), Error);
}

}  // namespace
}  // namespace thetad::tuning
