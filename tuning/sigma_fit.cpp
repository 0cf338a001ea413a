#include "tuning/sigma_fit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.hpp"

namespace thetad::tuning {

namespace {

// Per worker: the unpacked ΣT_i and the eigenvalue solver's storage.
struct Workspace {
  explicit Workspace(Eigen::Index n) : S(n, n), solver(n) {}
  Eigen::MatrixXd S;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
};

std::vector<Workspace> workspaces(const PackedSeries& series) {
  return std::vector<Workspace>(static_cast<std::size_t>(series.threads()), Workspace(series.states()));
}

}  // namespace

double sigma_max_symmetric(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& solver, const Eigen::MatrixXd& P) {
  solver.compute(P, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) throw Error("tuning: the symmetric eigenvalue solver did not converge");
  // Eigenvalues come sorted: the extremes hold the largest magnitude.
  return std::max(std::abs(solver.eigenvalues()[0]), std::abs(solver.eigenvalues()[P.rows() - 1]));
}

SigmaMatch::SigmaMatch(const ThetaDController& controller, const TuningRecord& record, int threads)
    : series_(controller, record, threads), sigma_sdre_(record.sigma_sdre) {}

Eigen::VectorXd SigmaMatch::sigma(const Eigen::VectorXd& k, const Eigen::VectorXd& l) const {
  Eigen::VectorXd out(samples());
  std::vector<Workspace> work = workspaces(series_);
  series_.for_each_sum(k, l, [&](int worker, Eigen::Index sample, const double* packed) {
    Workspace& w = work[static_cast<std::size_t>(worker)];
    unpack_lower(packed, w.S);
    out[sample] = sigma_max_symmetric(w.solver, w.S);
  });
  return out;
}

double SigmaMatch::residual(const Eigen::VectorXd& k, const Eigen::VectorXd& l, Weighting weighting) const {
  std::vector<Workspace> work = workspaces(series_);
  return series_.sum_over_samples(k, l, [&](int worker, Eigen::Index sample, const double* packed) {
    Workspace& w = work[static_cast<std::size_t>(worker)];
    unpack_lower(packed, w.S);
    const double difference = sigma_max_symmetric(w.solver, w.S) - sigma_sdre_[sample];
    const double scaled = weighting == Weighting::relative ? difference / sigma_sdre_[sample] : difference;
    return scaled * scaled;
  });
}

FitResult fit(const SigmaMatch& match, Weighting weighting, const FitOptions& options) {
  return fit([&](const Eigen::VectorXd& k, const Eigen::VectorXd& l) { return match.residual(k, l, weighting); },
             match.parameters(), options);
}

}  // namespace thetad::tuning
