#include "controllers/sdre_certificates.hpp"

#include <limits>

#include "core/error.hpp"

namespace thetad {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

}  // namespace

// The spectrum as the proof, as solve_care: the condition logged is the one a direct solve at that
// (F, B) reports.
SdreCertificates::SdreCertificates(const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R)
    : solver_(Q, R, CareMethod::automatic, StabilityProof::spectrum, ErrorEstimates::on),
      margin_(Q.rows(), R),
      condition_(kNan),
      forward_error_(kNan),
      stabilizability_(kNan) {}

std::vector<ControllerColumn> SdreCertificates::columns() {
  using Worst = ControllerColumn::Worst;
  return {{{"condition_estimate", ""}, Worst::largest},
          {{"forward_error_estimate", ""}, Worst::largest},
          {{"stabilizability_margin", ""}, Worst::smallest}};
}

void SdreCertificates::evaluate(const Eigen::MatrixXd& F, const Eigen::MatrixXd& B) {
  try {
    const CareResult& result = solver_.solve(F, B);
    condition_ = result.condition;
    forward_error_ = result.forward_error;
  } catch (const Error&) {
    condition_ = std::numeric_limits<double>::infinity();
    forward_error_ = kNan;
  }
  try {
    stabilizability_ = margin_.evaluate(F, B);
  } catch (const Error&) {
    stabilizability_ = kNan;
  }
}

void SdreCertificates::values(std::vector<double>& row) const {
  row.push_back(condition_);
  row.push_back(forward_error_);
  row.push_back(stabilizability_);
}

}  // namespace thetad
