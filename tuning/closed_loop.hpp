#pragma once

// The closed-loop objective: a controller (θ–D with its k_i, l_i, or any controller with its
// weights: parameterization.hpp) flown through the experiment library over a set of seeded draws
// of a scenario (parameter uncertainty, wind and noise of each seed), summary only, scored by the
// mean of its J, J_dev or RMS tracking error. It measures what a user of the controller wants from
// the tuning; the matches of ΣT_i to P (sigma_fit, entry_fit) only hope for it.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "core/sim/simulator.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/flight.hpp"
#include "settings/run_controls.hpp"
#include "tuning/parameterization.hpp"
#include "tuning/search.hpp"

namespace thetad::tuning {

enum class Metric {
  cost,       // J of Eq. (32) (sim::RunSummary::cost)
  rms_error,  // the RMS 3-D position error: the norm of the per-axis RMS tracking errors (m)
  cost_dev,   // J_dev, the comparison's score (sim::RunSummary::cost_dev, docs/model.md §7.2)
};
const char* metric_name(Metric metric);  // "cost", "rms_error_m", "cost_dev"
// Also takes "rms-error", rms_error_m's name before docs/glossary.md. Throws thetad::Error naming
// the known metrics.
Metric parse_metric(const std::string& name);
// The metric of a run; +∞ unless it completed (a diverged draw is worse than any that flew).
// Throws thetad::Error for J_dev of a run without it (a plant without trims).
double metric_value(const sim::RunSummary& summary, Metric metric);
// The mean metric over `summaries`; +∞ when one of them did not complete.
double mean_metric(const std::vector<sim::RunSummary>& summaries, Metric metric);

// The θ–D of `base` (a settings block, null: every default) with `terms` and k, l (empty: the
// block's own, else the defaults), labelled `label`.
ControllerSpec theta_d_spec(const YAML::Node& base, const std::string& label, int terms, const Eigen::VectorXd& k,
                            const Eigen::VectorXd& l);

// Flights of one scenario over seeded draws, for any controller spec, on `threads` workers (one
// Flight each). The draws are cut into fixed chunks of one, so the results are the same for any
// number of workers.
class DrawFlights {
 public:
  // `controls` as for Flight; the runs are summary-only whatever controls.summary_only says.
  // Throws thetad::Error for a bad scenario or controls, or when `parameters`' default controller
  // does not design.
  DrawFlights(const std::string& scenario, RunControls controls, Parameterization parameters, int threads);

  const Flight& flight() const { return *flights_.front(); }
  const Parameterization& parameters() const { return parameters_; }
  // Calls `observe` with the simulated time of the flights flown on the thread that calls fly()
  // (Flight::fly's observe): what it throws ends fly(), the other workers' flights at their next
  // progress sample, and propagates (a front end's way to stop a search: Python's Ctrl-C).
  void set_observer(std::function<void(double t)> observe) { observe_ = std::move(observe); }

  // The summaries of `spec` flown on each of `seeds`, in order.
  std::vector<sim::RunSummary> fly(const ControllerSpec& spec, const std::vector<std::uint64_t>& seeds);
  // The same for the controller at x of the parameterization.
  std::vector<sim::RunSummary> fly(const Eigen::VectorXd& x, const std::vector<std::uint64_t>& seeds) {
    return fly(parameters_.spec(x, parameters_.controller), seeds);
  }

 private:
  std::vector<std::unique_ptr<Flight>> flights_;  // one per worker: set_seed changes a Flight
  Parameterization parameters_;
  std::function<void(double t)> observe_;
};

// Minimises mean_metric over the `training` draws in the parameterization's box with search_box.
FitResult fit(DrawFlights& flights, const std::vector<std::uint64_t>& training, Metric metric, const FitOptions& options);

}  // namespace thetad::tuning
