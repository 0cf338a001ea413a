#pragma once

// Steps 2–3 of the k_i, l_i fit (spec §7.5): along a recorded SDRE trajectory, choose k, l of
// e_i(t) = 1 − k_i exp(−l_i t) (Eq. 25) to minimise Σ_k (σ_max[ΣT_i(x_k, t_k; k, l)] − σ_max[P(x_k)])².
//
// Only e_i depends on (k, l), and ΣT_i is a polynomial in the e_i with state-dependent matrix
// coefficients (ThetaDController::series_expansion). SigmaMatch computes those coefficients once
// per sample; every evaluation of the residual is then, per sample, a weighted sum of a few packed
// symmetric matrices and one symmetric eigenvalue problem: exact, without a Lyapunov solve.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "controllers/theta_d.hpp"
#include "tuning/record.hpp"

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
  // `controller` must have been reset at the recorded flight's start (its own k, l do not matter);
  // the expansions are computed on `threads` copies of it. Throws thetad::Error when the record
  // does not fit the controller's plant or a Lyapunov solve fails.
  SigmaMatch(const ThetaDController& controller, const TuningRecord& record, int threads);

  Eigen::Index samples() const { return static_cast<Eigen::Index>(elapsed_.size()); }
  int parameters() const { return terms_ - 1; }  // N − 1: one k and one l per term beyond T0
  const Eigen::VectorXd& sigma_sdre() const { return sigma_sdre_; }

  // σ_max(ΣT_i(x_k, t_k; k, l)) for every sample.
  Eigen::VectorXd sigma(const Eigen::VectorXd& k, const Eigen::VectorXd& l) const;
  // The least-squares residual; bit-identical for any number of threads (fixed chunks summed in order).
  double residual(const Eigen::VectorXd& k, const Eigen::VectorXd& l, Weighting weighting) const;

 private:
  // Calls visit(sample, σ_max) for every sample, over threads, chunk by chunk.
  void for_each_sigma(const Eigen::VectorXd& k, const Eigen::VectorXd& l,
                      const std::function<void(std::size_t chunk, Eigen::Index sample, double sigma)>& visit) const;

  int terms_;
  int threads_;
  Eigen::Index n_;
  std::vector<std::vector<int>> powers_;  // the monomials, the same for every sample
  std::vector<double> elapsed_;           // t_k − t0
  Eigen::VectorXd sigma_sdre_;
  // Per sample, per piece, the packed lower triangle (column by column) of the piece: samples ×
  // pieces × n(n+1)/2 doubles, with 5, 11, 29 pieces for N = 3, 4, 5.
  std::vector<double> packed_;
};

struct FitOptions {
  // "LN_BOBYQA" (default), "LN_SBPLX", "LN_NELDERMEAD": local from the start point;
  // "GN_DIRECT_L", "GN_ISRES": global over the box first, then LN_BOBYQA from its best point.
  std::string algorithm = "LN_BOBYQA";
  Weighting weighting = Weighting::absolute;
  // Box of spec §7.5 (docs/tuning.md gives the reasons): k_i ∈ [0, 1.5], l_i ∈ [0.01, 20].
  double k_lower = 0.0, k_upper = 1.5, l_lower = 0.01, l_upper = 20.0;
  // Start point; empty: the paper's k = l = 1 (spec §7.4).
  Eigen::VectorXd k_start, l_start;
  int max_local_evaluations = 1500;
  int max_global_evaluations = 800;
  double x_tolerance = 1e-9;  // relative, on k and l
  std::uint64_t seed = 1;     // GN_ISRES is randomized: NLopt's generator is seeded with this
  // Called after every evaluation with the count so far and the best residual so far.
  std::function<void(int evaluations, double best)> progress;
};

// The algorithms FitOptions::algorithm accepts.
const std::vector<std::string>& fit_algorithms();
// Throws thetad::Error on an unknown algorithm, reversed or non-finite bounds, l_lower < 0, a start
// point of the wrong size or outside the box, or non-positive evaluation limits.
void check_fit_options(const FitOptions& options, int parameters);

struct FitResult {
  Eigen::VectorXd k, l;
  double start_residual = 0.0;  // at the start point
  double residual = 0.0;        // at (k, l)
  int evaluations = 0;
  double seconds = 0.0;         // wall time of the search (the expansions are not included)
  std::string stop_reason;      // NLopt's, of the last stage
};

FitResult fit(const SigmaMatch& match, const FitOptions& options);

}  // namespace thetad::tuning
