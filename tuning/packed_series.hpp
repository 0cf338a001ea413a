#pragma once

// ΣT_i(x_k, t_k; k, l) at every sample of a recorded flight for any k, l, cheaply (docs/model.md §8.1).
//
// Only e_i depends on (k, l), and ΣT_i is a polynomial in the e_i with state-dependent matrix
// coefficients (ThetaDController::series_expansion). PackedSeries computes those coefficients once
// per sample and keeps their packed lower triangles; ΣT at a sample is then a weighted sum of a
// few packed symmetric matrices: exact, without a Lyapunov solve. The tuning objectives that
// compare ΣT_i with the SDRE's P (sigma_fit, entry_fit) are built on it.

#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "controllers/theta_d.hpp"
#include "tuning/record.hpp"

namespace thetad::tuning {

// The lower triangle of the symmetric n×n `matrix`, column by column: n(n+1)/2 values.
void pack_lower(const Eigen::MatrixXd& matrix, double* packed);
// Fills the lower triangle of `matrix` (n×n) from `packed`; the upper triangle is left as it was.
void unpack_lower(const double* packed, Eigen::MatrixXd& matrix);

class PackedSeries {
 public:
  // `controller` must have been reset at the recorded flight's start (its own k, l do not matter);
  // the expansions are computed on `threads` copies of it. Throws thetad::Error when the record
  // does not fit the controller's plant or a Lyapunov solve fails.
  PackedSeries(const ThetaDController& controller, const TuningRecord& record, int threads);

  Eigen::Index samples() const { return static_cast<Eigen::Index>(elapsed_.size()); }
  int parameters() const { return terms_ - 1; }  // N − 1: one k and one l per term beyond T0
  int threads() const { return threads_; }
  Eigen::Index states() const { return n_; }
  std::size_t packed_size() const { return static_cast<std::size_t>(n_ * (n_ + 1) / 2); }

  // Calls visit(worker, sample, packed ΣT_i(x_k, t_k; k, l)) for every sample, on threads() workers
  // in fixed chunks of samples.
  void for_each_sum(const Eigen::VectorXd& k, const Eigen::VectorXd& l,
                    const std::function<void(int worker, Eigen::Index sample, const double* packed)>& visit) const;
  // Σ_k term(worker, sample, packed ΣT_i) over the samples: bit-identical for any number of threads
  // (one partial sum per fixed chunk, added in chunk order).
  double sum_over_samples(const Eigen::VectorXd& k, const Eigen::VectorXd& l,
                          const std::function<double(int worker, Eigen::Index sample, const double* packed)>& term) const;

 private:
  void for_each_chunk_sum(const Eigen::VectorXd& k, const Eigen::VectorXd& l,
                          const std::function<void(int worker, std::size_t chunk, Eigen::Index sample, const double* packed)>& visit) const;

  int terms_;
  int threads_;
  Eigen::Index n_;
  std::vector<std::vector<int>> powers_;  // the monomials, the same for every sample
  std::vector<double> elapsed_;           // t_k − t0
  // Per sample, per piece, the packed lower triangle of the piece: samples × pieces × n(n+1)/2
  // doubles, with 5, 11, 29 pieces for N = 3, 4, 5.
  std::vector<double> packed_;
};

}  // namespace thetad::tuning
