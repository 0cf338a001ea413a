#include "tuning/held_out.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace thetad::tuning {

namespace {

std::vector<std::uint64_t> consecutive(std::uint64_t first, int count) {
  if (count < 0) throw Error("tuning: a negative number of draws (" + std::to_string(count) + ")");
  std::vector<std::uint64_t> seeds;
  for (int i = 0; i < count; ++i) seeds.push_back(first + static_cast<std::uint64_t>(i));
  return seeds;
}

PairedComparison compare(const HeldOutValidation& v, Metric metric, int resamples) {
  std::vector<double> defaults, tuned, differences;
  for (std::size_t i = 0; i < v.seeds.size(); ++i) {
    const double a = metric_value(v.default_runs[i], metric), b = metric_value(v.tuned_runs[i], metric);
    if (!std::isfinite(a) || !std::isfinite(b)) continue;
    defaults.push_back(a);
    tuned.push_back(b);
    differences.push_back(b - a);
  }
  if (differences.empty())
    throw Error("tuning: no held-out draw of " + v.scenario + " was completed by both the default and the tuned controller");
  return {metric, linear_quantile(defaults, 0.5), linear_quantile(tuned, 0.5),
          bootstrap_median(differences, v.bootstrap_seed, resamples)};
}

int not_completed(const std::vector<sim::RunSummary>& runs) {
  return static_cast<int>(std::count_if(runs.begin(), runs.end(),
                                        [](const sim::RunSummary& s) { return s.status != sim::RunStatus::completed; }));
}

}  // namespace

DrawSeeds draw_seeds(std::uint64_t training_first, int training, std::uint64_t held_out_first, int held_out) {
  DrawSeeds seeds{consecutive(training_first, training), consecutive(held_out_first, held_out)};
  for (std::uint64_t seed : seeds.held_out)
    if (std::find(seeds.training.begin(), seeds.training.end(), seed) != seeds.training.end())
      throw Error("tuning: the held-out draws must not repeat a training draw, and seed " + std::to_string(seed) +
                  " is in both (training seeds " + std::to_string(training_first) + " ... , held-out from " +
                  std::to_string(held_out_first) + ")");
  return seeds;
}

int HeldOutValidation::default_not_completed() const { return not_completed(default_runs); }
int HeldOutValidation::tuned_not_completed() const { return not_completed(tuned_runs); }

HeldOutValidation validate_held_out(DrawFlights& flights, const Eigen::VectorXd& tuned,
                                    const std::vector<std::uint64_t>& seeds, std::uint64_t bootstrap_seed, int resamples) {
  if (seeds.empty()) throw Error("tuning: the validation needs at least one held-out draw");
  HeldOutValidation v;
  v.scenario = flights.flight().scenario().name;
  v.seeds = seeds;
  v.resamples = resamples;
  v.bootstrap_seed = bootstrap_seed;
  v.default_runs = flights.fly(flights.parameters().default_spec(flights.parameters().controller), seeds);
  v.tuned_runs = flights.fly(tuned, seeds);
  v.cost = compare(v, Metric::cost, resamples);
  v.rms_error = compare(v, Metric::rms_error, resamples);
  const auto scored = [](const sim::RunSummary& s) { return s.cost_dev.has_value(); };
  if (std::all_of(v.default_runs.begin(), v.default_runs.end(), scored) &&
      std::all_of(v.tuned_runs.begin(), v.tuned_runs.end(), scored))
    v.cost_dev = compare(v, Metric::cost_dev, resamples);
  return v;
}

}  // namespace thetad::tuning
