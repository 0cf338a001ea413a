#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/controller_column.hpp"
#include "core/riccati.hpp"
#include "core/stabilizability_margin.hpp"

namespace thetad {

// The SDRE's certificates at the (F, B) of a sample's last Riccati solve (docs/model.md §8.4): the
// condition and forward-error estimates of that CARE (CareResult, docs/care-estimates.md) by one
// more cold solve with ErrorEstimates::on, and the stabilizability margin of (F, B). That solve is
// the price (about twice the step), hence `certificates: off` by default.
class SdreCertificates {
 public:
  SdreCertificates(const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R);

  // condition_estimate (largest is worst), forward_error_estimate (largest), stabilizability_margin
  // (smallest).
  static std::vector<ControllerColumn> columns();
  // Never throws: where the CARE has no stabilizing solution, the condition is +inf and the
  // forward error NaN; where LAPACK fails on the margin, it is NaN. Allocates nothing on success.
  void evaluate(const Eigen::MatrixXd& F, const Eigen::MatrixXd& B);
  // The values of the last evaluate(), in the order of columns().
  void values(std::vector<double>& row) const;

 private:
  CareSolver solver_;
  StabilizabilityMargin margin_;
  double condition_, forward_error_, stabilizability_;
};

}  // namespace thetad
