// The statistics of the held-out comparison: numpy's linear quantiles, and the percentile
// bootstrap of the median against cases whose answer is known in closed form.
#include <cmath>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tuning/paired_bootstrap.hpp"

namespace thetad::tuning {
namespace {

// numpy.quantile(values, q) (method "linear", its default).
TEST(LinearQuantile, MatchesNumpy) {
  EXPECT_EQ(linear_quantile({3.0, 1.0, 2.0}, 0.5), 2.0);
  EXPECT_EQ(linear_quantile({4.0, 1.0, 3.0, 2.0}, 0.5), 2.5);
  EXPECT_EQ(linear_quantile({4.0, 1.0, 3.0, 2.0}, 0.25), 1.75);
  EXPECT_NEAR(linear_quantile({10, 9, 8, 7, 6, 5, 4, 3, 2, 1}, 0.9), 9.1, 1e-12);
  EXPECT_EQ(linear_quantile({5.0}, 0.975), 5.0);
  EXPECT_EQ(linear_quantile({-1.0, 7.0}, 1.0), 7.0);
  EXPECT_THROW(linear_quantile({}, 0.5), Error);
}

// Two values a < b: a resample's median is a, b or (a+b)/2 with probabilities 1/4, 1/4, 1/2, so
// the 2.5 % and 97.5 % points of 2000 resamples are a and b.
TEST(BootstrapMedian, TwoValuesGiveTheirRangeAsInterval) {
  const BootstrapMedian result = bootstrap_median({2.0, 6.0}, 11);
  EXPECT_EQ(result.count, 2);
  EXPECT_EQ(result.median, 4.0);
  EXPECT_EQ(result.low, 2.0);
  EXPECT_EQ(result.high, 6.0);
}

TEST(BootstrapMedian, IsReproducibleAndBracketsTheMedian) {
  const std::vector<double> values{-3.1, 0.4, 1.5, -0.2, 2.2, 0.9, -1.7, 0.1, 3.3, 0.6, -0.5, 1.1};
  const BootstrapMedian a = bootstrap_median(values, 5), b = bootstrap_median(values, 5);
  EXPECT_EQ(a.low, b.low);
  EXPECT_EQ(a.high, b.high);
  EXPECT_EQ(a.median, 0.5);
  EXPECT_LT(a.low, a.median);
  EXPECT_GT(a.high, a.median);
  // A resample's median falls below −0.5 (above 1.5) only when about 6 of its 12 values are the
  // two smallest (largest): a chance near 1 %, inside the 2.5 % of each tail.
  EXPECT_GE(a.low, -0.5);
  EXPECT_LE(a.high, 1.5);
}

TEST(BootstrapMedian, EqualValuesHaveAnIntervalOfZeroWidthAndOneValueNone) {
  const BootstrapMedian same = bootstrap_median({0.0, 0.0, 0.0}, 1);
  EXPECT_EQ(same.low, 0.0);
  EXPECT_EQ(same.high, 0.0);
  const BootstrapMedian one = bootstrap_median({4.0}, 1);
  EXPECT_EQ(one.median, 4.0);
  EXPECT_TRUE(std::isnan(one.low) && std::isnan(one.high));
  EXPECT_THROW(bootstrap_median({}, 1), Error);
  EXPECT_THROW(bootstrap_median({1.0, 2.0}, 1, 0), Error);
  EXPECT_THROW(bootstrap_median({1.0, 2.0}, 1, 100, 1.0), Error);
}

}  // namespace
}  // namespace thetad::tuning
