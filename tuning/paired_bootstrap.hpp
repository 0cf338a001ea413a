#pragma once

// The paired comparison of a tuned θ–D with the default one on the same draws: the median of the
// per-draw differences with a seeded percentile bootstrap interval. The same statistic as the
// campaign reports (scripts/campaign_stats.py: scipy.stats.bootstrap, method "percentile"), in
// C++ so that `thetad tune` prints it without Python; no C++ library the project depends on has
// a bootstrap. Quantiles are linear (Hyndman & Fan type 7, numpy's default).

#include <cstdint>
#include <vector>

namespace thetad::tuning {

// The q-quantile (0 ≤ q ≤ 1) of `values` (not empty) by linear interpolation between order statistics.
double linear_quantile(std::vector<double> values, double q);

struct BootstrapMedian {
  int count = 0;
  double median = 0.0;
  double low = 0.0, high = 0.0;  // the percentile interval; NaN for fewer than 2 values
};

// The median of `values` and its percentile bootstrap interval at `confidence` from `resamples`
// resamples drawn with std::mt19937_64 seeded with `seed`: the same values and seed give the same
// interval, bit for bit. Throws thetad::Error for no values, resamples < 1 or confidence outside (0, 1).
BootstrapMedian bootstrap_median(const std::vector<double>& values, std::uint64_t seed, int resamples = 2000,
                                 double confidence = 0.95);

}  // namespace thetad::tuning
