#include "core/care_diagnosis.hpp"

#include <algorithm>
#include <complex>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "core/care_weights.hpp"

namespace thetad {

using care::num;

std::string broken_care_precondition(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                     const Eigen::Ref<const Eigen::MatrixXd>& B,
                                     const Eigen::Ref<const Eigen::MatrixXd>& Q) {
  const Eigen::Index n = A.rows();
  const double scale = std::max({1.0, A.norm(), B.norm(), Q.norm()});
  const double tolerance = 100.0 * static_cast<double>(n) * std::numeric_limits<double>::epsilon() * scale;
  const Eigen::VectorXcd modes = Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
  const auto smallest_singular_value = [](const Eigen::MatrixXcd& M) {
    return Eigen::JacobiSVD<Eigen::MatrixXcd>(M).singularValues().minCoeff();
  };
  for (const std::complex<double> lambda : modes) {
    const Eigen::MatrixXcd shifted = A.cast<std::complex<double>>() - lambda * Eigen::MatrixXcd::Identity(n, n);
    const std::string mode = "λ = " + num(lambda.real()) + (lambda.imag() >= 0 ? "+" : "") + num(lambda.imag()) + "i";
    if (lambda.real() >= -tolerance) {
      Eigen::MatrixXcd reach(n, n + B.cols());
      reach << shifted, B.cast<std::complex<double>>();
      const double sigma = smallest_singular_value(reach);
      if (sigma <= tolerance)
        return "the pair (A, B) is not stabilizable: the mode " + mode + " of A is not controllable (σ_min[A − λI, B] = " +
               num(sigma) + ")";
    }
    if (std::abs(lambda.real()) <= tolerance) {
      Eigen::MatrixXcd see(2 * n, n);
      see << shifted, Q.cast<std::complex<double>>();
      const double sigma = smallest_singular_value(see);
      if (sigma <= tolerance)
        return "(Q, A) is not detectable: the mode " + mode + " of A on the imaginary axis is not seen by Q "
               "(σ_min[A − λI; Q] = " + num(sigma) + ")";
    }
  }
  return {};
}

void rethrow_with_diagnosis(const Error& error, const Eigen::Ref<const Eigen::MatrixXd>& A,
                            const Eigen::Ref<const Eigen::MatrixXd>& B, const Eigen::Ref<const Eigen::MatrixXd>& Q) {
  const std::string broken = broken_care_precondition(A, B, Q);
  if (broken.empty()) throw error;
  // The solver's own words, less the "CARE: " and the generic hint that `broken` now makes precise.
  std::string solver = std::string(error.what()).substr(6);
  if (const auto hint = solver.find(care::kStabilizabilityHint); hint != std::string::npos)
    solver.erase(hint, std::string(care::kStabilizabilityHint).size());
  throw Error("CARE: " + broken + " (" + solver + ")");
}

}  // namespace thetad
