#include "core/sim/run_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace thetad::sim {

RunMetrics::RunMetrics(Eigen::VectorXd state_weights, Eigen::VectorXd input_weights, Eigen::Index tracked,
                       double period, std::int64_t samples, bool timing)
    : state_weights_(std::move(state_weights)),
      input_weights_(std::move(input_weights)),
      period_(period),
      timing_(timing),
      error_square_sum_(Eigen::VectorXd::Zero(tracked)),
      max_error_(Eigen::VectorXd::Zero(tracked)),
      command_square_sum_(Eigen::VectorXd::Zero(input_weights_.size())) {
  if (timing_) compute_ns_.reserve(static_cast<std::size_t>(samples));
}

void RunMetrics::add(const Eigen::VectorXd& error, const Eigen::VectorXd& v_track, const Eigen::VectorXd& command,
                     std::int64_t compute_ns) {
  // J (the helicopter's Eq. 32, docs/model.md §7) by left rectangles at the controller rate.
  cost_ += 0.5 * (v_track.cwiseAbs2().dot(state_weights_) + command.cwiseAbs2().dot(input_weights_)) * period_;
  error_square_sum_ += error.cwiseAbs2();
  max_error_ = max_error_.cwiseMax(error.cwiseAbs());
  command_square_sum_ += command.cwiseAbs2();
  if (timing_ && compute_ns >= 0) compute_ns_.push_back(compute_ns);
  ++samples_;
}

void RunMetrics::finish(RunSummary& summary) {
  summary.controller_samples = samples_;
  summary.cost = cost_;
  summary.max_tracking_error = max_error_;
  summary.rms_tracking_error = Eigen::VectorXd::Zero(error_square_sum_.size());
  summary.command_rms = Eigen::VectorXd::Zero(command_square_sum_.size());
  if (samples_ > 0) {
    const auto n = static_cast<double>(samples_);
    summary.rms_tracking_error = (error_square_sum_ / n).cwiseSqrt();
    summary.command_rms = (command_square_sum_ / n).cwiseSqrt();
  }
  if (compute_ns_.empty()) return;
  std::sort(compute_ns_.begin(), compute_ns_.end());
  const std::size_t n = compute_ns_.size();
  double sum = 0.0;
  for (const auto s : compute_ns_) sum += static_cast<double>(s);
  summary.compute_ns_mean = sum / static_cast<double>(n);
  // Nearest rank, as thetad bench's median (docs/glossary.md "Compute time"): one definition for both.
  summary.compute_ns_median = nearest_rank(compute_ns_, 0.5);
  summary.compute_ns_p99 = nearest_rank(compute_ns_, 0.99);
}

}  // namespace thetad::sim
