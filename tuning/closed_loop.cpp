#include "tuning/closed_loop.hpp"

#include <algorithm>
#include <atomic>
#include <limits>

#include "controllers/theta_d.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"

namespace thetad::tuning {

const char* metric_name(Metric metric) {
  switch (metric) {
    case Metric::cost: return "cost";
    case Metric::rms_error: return "rms_error_m";
    default: return "cost_dev";
  }
}

Metric parse_metric(const std::string& name) {
  if (name == "cost") return Metric::cost;
  // "rms-error", "cost-dev": the names before docs/glossary.md ("θ–D settings and tuning"), still
  // accepted so that earlier command lines and Python calls keep working.
  if (name == "rms_error_m" || name == "rms-error") return Metric::rms_error;
  if (name == "cost_dev" || name == "cost-dev") return Metric::cost_dev;
  throw Error("tuning: unknown metric '" + name + "' (known: cost, rms_error_m, cost_dev)");
}

double metric_value(const sim::RunSummary& summary, Metric metric) {
  if (metric == Metric::cost_dev && !summary.cost_dev)
    throw Error("tuning: the metric cost_dev needs J_dev, which this plant's runs do not have (no trims)");
  if (summary.status != sim::RunStatus::completed) return std::numeric_limits<double>::infinity();
  switch (metric) {
    case Metric::cost: return summary.cost;
    case Metric::rms_error: return summary.rms_tracking_error.norm();
    default: return *summary.cost_dev;
  }
}

double mean_metric(const std::vector<sim::RunSummary>& summaries, Metric metric) {
  double sum = 0.0;
  for (const sim::RunSummary& summary : summaries) sum += metric_value(summary, metric);
  return sum / static_cast<double>(summaries.size());
}

ControllerSpec theta_d_spec(const YAML::Node& base, const std::string& label, int terms, const Eigen::VectorXd& k,
                            const Eigen::VectorXd& l) {
  YAML::Node block = base ? YAML::Clone(base) : YAML::Node(YAML::NodeType::Map);
  block[theta_d_keys::terms] = terms;
  const auto values = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  if (k.size() > 0) block[theta_d_keys::k] = values(k);
  if (l.size() > 0) block[theta_d_keys::l] = values(l);
  return {label, "theta-d", block, {}, {}};
}

DrawFlights::DrawFlights(const std::string& scenario, RunControls controls, Parameterization parameters, int threads)
    : parameters_(std::move(parameters)) {
  controls.summary_only = true;
  for (int w = 0; w < std::max(1, threads); ++w) flights_.push_back(std::make_unique<Flight>(scenario, controls));
  flight().prepare(parameters_.default_spec(parameters_.controller));  // a block that does not design fails here
}

std::vector<sim::RunSummary> DrawFlights::fly(const ControllerSpec& spec, const std::vector<std::uint64_t>& seeds) {
  std::vector<sim::RunSummary> summaries(seeds.size());
  const int workers = static_cast<int>(std::min(flights_.size(), std::max<std::size_t>(1, seeds.size())));
  // The calling thread is worker 0 (for_each_chunk): the observer watches its flights; once it has
  // thrown, the others stop at their next sample, and for_each_chunk rethrows worker 0's exception.
  std::atomic<bool> stopping{false};
  struct Stopped {};
  const std::function<void(double)> watched = [&](double t) {
    try {
      observe_(t);
    } catch (...) {
      stopping = true;
      throw;
    }
  };
  const std::function<void(double)> stop_when_told = [&](double) {
    if (stopping) throw Stopped{};
  };
  for_each_chunk(seeds.size(), 1, workers, [&](int worker, std::size_t draw, std::size_t, std::size_t) {
    Flight& flight = *flights_[static_cast<std::size_t>(worker)];
    flight.set_seed(seeds[draw]);
    PreparedController prepared = flight.prepare(spec);
    const std::function<void(double)> none;
    summaries[draw] = flight.fly(prepared, nullptr, {}, !observe_ ? none : worker == 0 ? watched : stop_when_told).summary;
  });
  return summaries;
}

FitResult fit(DrawFlights& flights, const std::vector<std::uint64_t>& training, Metric metric, const FitOptions& options) {
  if (training.empty()) throw Error("tuning: the closed-loop objective needs at least one training draw");
  const Parameterization& parameters = flights.parameters();
  FitResult result = search_box([&](const Eigen::VectorXd& x) { return mean_metric(flights.fly(x, training), metric); },
                                parameters.box, options);
  if (parameters.kind == "series") {
    const auto p = result.x.size() / 2;
    result.k = result.x.head(p);
    result.l = result.x.tail(p);
  }
  return result;
}

}  // namespace thetad::tuning
