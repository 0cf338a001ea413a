#include "tuning/paired_bootstrap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "core/error.hpp"

namespace thetad::tuning {

double linear_quantile(std::vector<double> values, double q) {
  if (values.empty()) throw Error("tuning: the quantile of no values");
  const double position = q * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(below), values.end());
  const double lower = values[below];
  if (below + 1 == values.size()) return lower;
  const double upper = *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(below) + 1, values.end());
  return lower + (position - static_cast<double>(below)) * (upper - lower);
}

BootstrapMedian bootstrap_median(const std::vector<double>& values, std::uint64_t seed, int resamples, double confidence) {
  if (values.empty()) throw Error("tuning: a bootstrap of no values");
  if (resamples < 1) throw Error("tuning: the bootstrap needs at least 1 resample, got " + std::to_string(resamples));
  if (!(confidence > 0.0 && confidence < 1.0))
    throw Error("tuning: the bootstrap confidence must lie in (0, 1), got " + std::to_string(confidence));
  BootstrapMedian result;
  result.count = static_cast<int>(values.size());
  result.median = linear_quantile(values, 0.5);
  if (values.size() < 2) {
    result.low = result.high = std::numeric_limits<double>::quiet_NaN();
    return result;
  }
  std::mt19937_64 generator(seed);
  std::uniform_int_distribution<std::size_t> pick(0, values.size() - 1);
  std::vector<double> medians(static_cast<std::size_t>(resamples)), resample(values.size());
  for (double& median : medians) {
    for (double& value : resample) value = values[pick(generator)];
    median = linear_quantile(resample, 0.5);
  }
  const double tail = 0.5 * (1.0 - confidence);
  result.low = linear_quantile(medians, tail);
  result.high = linear_quantile(medians, 1.0 - tail);
  return result;
}

}  // namespace thetad::tuning
