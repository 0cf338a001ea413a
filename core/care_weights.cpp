#include "core/care_weights.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/error.hpp"
#include "core/machine_epsilon.hpp"

namespace thetad::care {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;

// Smallest and largest eigenvalue of a symmetric matrix. Weights are usually diagonal: a diagonal
// needs no eigensolver.
std::pair<double, double> spectrum_range(const MatrixXd& M) {
  if (M.isDiagonal(0.0)) return {M.diagonal().minCoeff(), M.diagonal().maxCoeff()};
  const Eigen::VectorXd eigenvalues = M.selfadjointView<Eigen::Lower>().eigenvalues();
  return {eigenvalues(0), eigenvalues(eigenvalues.size() - 1)};
}

}  // namespace

std::string num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

std::string shape(const MatrixRef& M) { return std::to_string(M.rows()) + "x" + std::to_string(M.cols()); }

void fail(const std::string& what) { fail("CARE", what); }

void fail(const char* equation, const std::string& what) { throw Error(std::string(equation) + ": " + what); }

void check_symmetric(const char* name, const MatrixRef& M, const char* equation) {
  const double asymmetry = frobenius_norm(M - M.transpose());
  if (asymmetry > 1e-10 * frobenius_norm(M))
    fail(equation, std::string(name) + " is not symmetric (‖" + name + " − " + name + "'‖_F = " + num(asymmetry) +
                       ", ‖" + name + "‖_F = " + num(frobenius_norm(M)) + ")");
}

const char* const kStabilizabilityHint =
    "; the pair (A, B) may not be stabilizable or (Q, A) may have an unobservable mode on the "
    "imaginary axis (not detectable)";

void check_inputs(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R, const char* equation) {
  const Index n = A.rows();
  if (n == 0 || A.cols() != n) fail(equation, "A must be square and non-empty, but A is " + shape(A));
  if (B.rows() != n)
    fail(equation, "B is " + shape(B) + " but A is " + shape(A) + " (B needs " + std::to_string(n) + " rows)");
  if (B.cols() == 0) fail(equation, "B has no columns");
  if (Q.rows() != n || Q.cols() != n) fail(equation, "Q is " + shape(Q) + " but A is " + shape(A));
  if (R.rows() != B.cols() || R.cols() != B.cols())
    fail(equation, "R is " + shape(R) + " but B has " + std::to_string(B.cols()) + " columns");
  const std::pair<const char*, const MatrixRef*> all[] = {{"A", &A}, {"B", &B}, {"Q", &Q}, {"R", &R}};
  for (const auto& [name, M] : all)
    if (!M->allFinite()) fail(equation, std::string(name) + " has a non-finite entry (NaN or Inf)");
}

void check_cross_term(const char* name, const MatrixRef& S, const MatrixRef& B, const char* equation) {
  if (S.rows() != B.rows() || S.cols() != B.cols())
    fail(equation, std::string(name) + " is " + shape(S) + " but B is " + shape(B) + " (" + name + " needs the shape of B)");
  if (!S.allFinite()) fail(equation, std::string(name) + " has a non-finite entry (NaN or Inf)");
}

WithoutCrossTerm eliminate_cross_term(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& S,
                                      const Eigen::LDLT<MatrixXd>& R) {
  WithoutCrossTerm reduced{A, Q, R.solve(S.transpose())};
  reduced.A.noalias() -= B * reduced.RinvSt;
  reduced.Q.noalias() -= S * reduced.RinvSt;
  reduced.Q = 0.5 * (reduced.Q + reduced.Q.transpose()).eval();
  return reduced;
}

Weights prepare_weights(const MatrixRef& Q, const MatrixRef& R) {
  check_symmetric("Q", Q);
  check_symmetric("R", R);
  Weights w;
  w.Q = 0.5 * (Q + Q.transpose());
  w.q_norm = frobenius_norm(w.Q);
  const auto [q_min, q_max] = spectrum_range(w.Q);
  const double q_scale = std::max(std::abs(q_min), std::abs(q_max));
  if (q_min < -100.0 * static_cast<double>(Q.rows()) * kEps * q_scale)
    fail("Q is not positive semi-definite (min eigenvalue " + num(q_min) + ", max " + num(q_max) + ")");

  const MatrixXd R_sym = 0.5 * (R + R.transpose());
  const auto [r_min, r_max] = spectrum_range(R_sym);
  // Below m·eps·max the Cholesky factor, hence G, carries no correct digit.
  if (!(r_min > static_cast<double>(R.rows()) * kEps * r_max))
    fail("R is not symmetric positive definite (min eigenvalue " + num(r_min) + ", max " + num(r_max) + ")");
  w.L = Eigen::LLT<MatrixXd>(R_sym).matrixL();
  return w;
}

void set_input_matrix(Weights& w, const MatrixRef& B) {
  w.W = B.transpose();
  w.L.triangularView<Eigen::Lower>().solveInPlace(w.W);
}

double care_residual(const MatrixRef& A, const Weights& w, const MatrixXd& P, const MatrixXd& WP, MatrixXd& Res) {
  Res.noalias() = A.transpose() * P;
  const double AtP_norm = frobenius_norm(Res);
  // Res + Res' in place, by pairs: no temporary for the transpose on the hot path.
  for (Index j = 0; j < Res.cols(); ++j) {
    Res(j, j) *= 2.0;
    for (Index i = 0; i < j; ++i) Res(i, j) = Res(j, i) = Res(i, j) + Res(j, i);
  }
  Res.noalias() -= WP.transpose() * WP;
  Res += w.Q;
  return AtP_norm;
}

void symmetrize(MatrixXd& P) {
  for (Index j = 0; j < P.cols(); ++j)
    for (Index i = 0; i < j; ++i) P(i, j) = P(j, i) = 0.5 * (P(i, j) + P(j, i));
}

double residual_to_terms(double residual_norm, double q_norm, double AtP_norm, double PGP_norm) {
  return residual_norm == 0.0 ? 0.0 : residual_norm / (q_norm + 2.0 * AtP_norm + PGP_norm);
}

double frobenius_norm(const MatrixRef& M) {
  const double norm = M.norm();
  if (norm > 1e-140 && norm < 1e140) return norm;
  return M.stableNorm();
}

double relative_to_q(double residual_norm, const Weights& w) {
  return residual_norm / std::max(1.0, w.q_norm);
}

double normwise_residual(double residual_norm, double q_norm, double a_norm, double g_norm, double p_norm) {
  return residual_norm / (q_norm + 2.0 * a_norm * p_norm + g_norm * p_norm * p_norm);
}

}  // namespace thetad::care
