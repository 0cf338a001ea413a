#include "tuning/entry_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace thetad::tuning {

EntryMatch::EntryMatch(const ThetaDController& controller, const TuningRecord& record, const Eigen::MatrixXd& targets,
                       double floor, int threads)
    : series_(controller, record, threads), floor_(floor), targets_(targets), weights_(targets.rows(), targets.cols()) {
  if (!(floor > 0.0 && floor <= 1.0))
    throw Error("tuning: the entry scale floor must lie in (0, 1], got " + std::to_string(floor));
  if (targets.rows() != static_cast<Eigen::Index>(series_.packed_size()) || targets.cols() != series_.samples())
    throw Error("tuning: " + std::to_string(targets.cols()) + " target matrices of " + std::to_string(targets.rows()) +
                " packed entries for " + std::to_string(series_.samples()) + " samples of " +
                std::to_string(series_.packed_size()));
  const Eigen::Index n = series_.states();
  Eigen::MatrixXd P(n, n);
  for (Eigen::Index k = 0; k < targets.cols(); ++k) {
    unpack_lower(targets.col(k).data(), P);
    for (Eigen::Index r = 0; r < n; ++r)
      if (!(P(r, r) > 0.0))
        throw Error("tuning: P at sample " + std::to_string(k) + " has P(" + std::to_string(r) + ", " + std::to_string(r) +
                    ") = " + std::to_string(P(r, r)) + ": the entry scales need a positive diagonal");
    Eigen::Index index = 0;
    for (Eigen::Index c = 0; c < n; ++c)
      for (Eigen::Index r = c; r < n; ++r, ++index) {
        const double scale = std::max(std::abs(P(r, c)), floor * std::sqrt(P(r, r) * P(c, c)));
        weights_(index, k) = (r == c ? 1.0 : 2.0) / (scale * scale);
      }
  }
}

double EntryMatch::residual(const Eigen::VectorXd& k, const Eigen::VectorXd& l) const {
  const auto size = static_cast<Eigen::Index>(series_.packed_size());
  return series_.sum_over_samples(k, l, [&](int, Eigen::Index sample, const double* packed) {
    const Eigen::Map<const Eigen::VectorXd> sum(packed, size);
    return (weights_.col(sample).array() * (sum - targets_.col(sample)).array().square()).sum();
  });
}

double EntryMatch::rms_relative_error(const Eigen::VectorXd& k, const Eigen::VectorXd& l) const {
  const auto n = static_cast<double>(series_.states());
  return std::sqrt(residual(k, l) / (static_cast<double>(samples()) * n * n));
}

FitResult fit(const EntryMatch& match, const FitOptions& options) {
  return fit([&](const Eigen::VectorXd& k, const Eigen::VectorXd& l) { return match.residual(k, l); },
             match.parameters(), options);
}

}  // namespace thetad::tuning
