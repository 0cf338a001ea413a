#pragma once

// The paper's objective for k_i, l_i of e_i(t) = 1 − k_i exp(−l_i t) (Eq. 25, docs/model.md §8.1): along a
// recorded SDRE trajectory, Σ_k (σ_max[ΣT_i(x_k, t_k; k, l)] − σ_max[P(x_k)])². Each evaluation
// is, per sample, a weighted sum of packed pieces (PackedSeries) and one symmetric eigenvalue problem.

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "controllers/theta_d.hpp"
#include "tuning/packed_series.hpp"
#include "tuning/record.hpp"
#include "tuning/search.hpp"

namespace thetad::tuning {

// σ_max of a symmetric matrix (its largest |eigenvalue|), reading the lower triangle only, with
// the caller's solver so that repeated calls reuse its storage.
double sigma_max_symmetric(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& solver, const Eigen::MatrixXd& P);

enum class Weighting {
  absolute,  // (σ_θD − σ_P)², as the paper states it
  relative,  // ((σ_θD − σ_P) / σ_P)²: every sample counts alike whatever the size of P there
};

class SigmaMatch {
 public:
  // See PackedSeries for `controller` and `threads`.
  SigmaMatch(const ThetaDController& controller, const TuningRecord& record, int threads);

  Eigen::Index samples() const { return series_.samples(); }
  int parameters() const { return series_.parameters(); }
  const Eigen::VectorXd& sigma_sdre() const { return sigma_sdre_; }

  // σ_max(ΣT_i(x_k, t_k; k, l)) for every sample.
  Eigen::VectorXd sigma(const Eigen::VectorXd& k, const Eigen::VectorXd& l) const;
  // The least-squares residual; bit-identical for any number of threads.
  double residual(const Eigen::VectorXd& k, const Eigen::VectorXd& l, Weighting weighting) const;

 private:
  PackedSeries series_;
  Eigen::VectorXd sigma_sdre_;
};

// The fit of docs/model.md §8.1: `fit` of search.hpp on match.residual(k, l, weighting).
FitResult fit(const SigmaMatch& match, Weighting weighting, const FitOptions& options);

}  // namespace thetad::tuning
