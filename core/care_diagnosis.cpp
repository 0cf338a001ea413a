#include "core/care_diagnosis.hpp"

#include <algorithm>
#include <complex>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "core/care_weights.hpp"

namespace thetad {

using care::num;

namespace {

// `M` multiplied by a positive number so that ‖M‖_F = `scale` (zero stays zero), divided first so
// that no ratio of norms overflows (‖M‖_F = 1e-300 against ‖A‖_F = 1e10).
Eigen::MatrixXd scaled_to(const Eigen::Ref<const Eigen::MatrixXd>& M, double scale) {
  const double norm = care::frobenius_norm(M);
  return norm > 0.0 ? Eigen::MatrixXd(M / norm * scale) : Eigen::MatrixXd(M);
}

}  // namespace

std::string broken_riccati_precondition(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                        const Eigen::Ref<const Eigen::MatrixXd>& B_given,
                                        const Eigen::Ref<const Eigen::MatrixXd>& Q_given, TimeDomain domain) {
  const Eigen::Index n = A.rows();
  // Stabilizability of (A, B) and detectability of (Q, A) do not change when B or Q is multiplied
  // by a positive number, but σ_min[A − λI, B] and σ_min[A − λI; Q] do: with B and Q scaled to
  // ‖A‖_F the tolerance, relative to ‖A‖_F (the size of the rounding in A's eigenvalues), means the
  // same for weights of any size. Against max(1, ‖A‖, ‖B‖, ‖Q‖) instead, Q scaled by 1e-170 read
  // as blind to every mode on the axis, and Q scaled by 1e200 put every mode of A on the axis.
  const double scale = care::frobenius_norm(A) > 0.0 ? care::frobenius_norm(A) : 1.0;
  const Eigen::MatrixXd B = scaled_to(B_given, scale), Q = scaled_to(Q_given, scale);
  const double tolerance = 100.0 * static_cast<double>(n) * std::numeric_limits<double>::epsilon() * scale;
  const Eigen::VectorXcd modes = Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
  const auto smallest_singular_value = [](const Eigen::MatrixXcd& M) {
    return Eigen::JacobiSVD<Eigen::MatrixXcd>(M).singularValues().minCoeff();
  };
  // The distance outside the stable region: Re λ, or |λ| − 1. On the unit circle the rounding of
  // an eigenvalue is relative to max(1, ‖A‖_F) rather than to ‖A‖_F: |λ| = 1 is a fixed radius.
  const bool continuous = domain == TimeDomain::continuous;
  const double boundary_tolerance = continuous ? tolerance : tolerance / scale * std::max(1.0, scale);
  const auto outside = [&](std::complex<double> lambda) { return continuous ? lambda.real() : std::abs(lambda) - 1.0; };
  const char* const boundary = continuous ? "the imaginary axis" : "the unit circle";
  for (const std::complex<double> lambda : modes) {
    const Eigen::MatrixXcd shifted = A.cast<std::complex<double>>() - lambda * Eigen::MatrixXcd::Identity(n, n);
    const std::string mode = "λ = " + num(lambda.real()) + (lambda.imag() >= 0 ? "+" : "") + num(lambda.imag()) + "i";
    if (outside(lambda) >= -boundary_tolerance) {
      Eigen::MatrixXcd reach(n, n + B.cols());
      reach << shifted, B.cast<std::complex<double>>();
      const double sigma = smallest_singular_value(reach);
      if (sigma <= tolerance)
        return "the pair (A, B) is not stabilizable: the mode " + mode + " of A is not controllable (σ_min[A − λI, B] = " +
               num(sigma) + ", B scaled to ‖A‖_F)";
    }
    if (std::abs(outside(lambda)) <= boundary_tolerance) {
      Eigen::MatrixXcd see(2 * n, n);
      see << shifted, Q.cast<std::complex<double>>();
      const double sigma = smallest_singular_value(see);
      if (sigma <= tolerance)
        return "(Q, A) is not detectable: the mode " + mode + " of A on " + boundary + " is not seen by Q "
               "(σ_min[A − λI; Q] = " + num(sigma) + ", Q scaled to ‖A‖_F)";
    }
  }
  return {};
}

std::string broken_care_precondition(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                     const Eigen::Ref<const Eigen::MatrixXd>& B,
                                     const Eigen::Ref<const Eigen::MatrixXd>& Q) {
  return broken_riccati_precondition(A, B, Q, TimeDomain::continuous);
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
