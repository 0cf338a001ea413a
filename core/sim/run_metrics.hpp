#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/sim/run_summary.hpp"

namespace thetad::sim {

// The figures of a RunSummary, accumulated sample by sample while a run flies: RMS and max
// position error, RMS command, the cost J and the control step's wall-time statistics. Sized at
// construction: add() allocates nothing.
class RunMetrics {
 public:
  // `state_weights`, `input_weights`: the diagonals of Q and R in J; `tracked`: how many tracked
  // states the errors have; `period`: the controller period T_c; `samples`: the run's controller
  // samples (for the timing record, when `timing`).
  RunMetrics(Eigen::VectorXd state_weights, Eigen::VectorXd input_weights, Eigen::Index tracked, double period,
             std::int64_t samples, bool timing);

  // One controller sample: the tracked states' true errors, the tracking vector on the true state,
  // the commanded u and the control() wall time (negative: the sample computed nothing, the flight
  // computer was busy).
  void add(const Eigen::VectorXd& error, const Eigen::VectorXd& v_track, const Eigen::VectorXd& command,
           std::int64_t compute_ns);

  // Writes the figures into `summary` (controller_samples, errors, effort, cost, timing).
  void finish(RunSummary& summary);

 private:
  Eigen::VectorXd state_weights_, input_weights_;
  double period_;
  bool timing_;
  std::int64_t samples_ = 0;
  double cost_ = 0.0;
  Eigen::VectorXd error_square_sum_;
  Eigen::VectorXd max_error_;
  Eigen::VectorXd command_square_sum_;
  std::vector<std::int64_t> compute_ns_;
};

// The nearest-rank q-quantile of ascending `sorted` (not empty): the smallest value with at least
// a fraction q of the values at or below it.
template <class Value>
double nearest_rank(const std::vector<Value>& sorted, double q) {
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return static_cast<double>(sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1]);
}

}  // namespace thetad::sim
