#include "core/riccati.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/lapack.hpp"
#include "core/lyapunov.hpp"

namespace thetad {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using MatrixRef = Eigen::Ref<const MatrixXd>;

constexpr double kEps = std::numeric_limits<double>::epsilon();

std::string num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

std::string shape(const MatrixRef& M) {
  return std::to_string(M.rows()) + "x" + std::to_string(M.cols());
}

[[noreturn]] void fail(const std::string& what) { throw Error("CARE: " + what); }

const char* const kStabilizabilityHint =
    "; the pair (A, B) may not be stabilizable or (Q, A) may have an unobservable mode on the "
    "imaginary axis (not detectable)";

void check_inputs(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R) {
  const Index n = A.rows();
  if (n == 0 || A.cols() != n) fail("A must be square and non-empty, but A is " + shape(A));
  if (B.rows() != n) fail("B is " + shape(B) + " but A is " + shape(A) + " (B needs " + std::to_string(n) + " rows)");
  if (B.cols() == 0) fail("B has no columns");
  if (Q.rows() != n || Q.cols() != n) fail("Q is " + shape(Q) + " but A is " + shape(A));
  if (R.rows() != B.cols() || R.cols() != B.cols())
    fail("R is " + shape(R) + " but B has " + std::to_string(B.cols()) + " columns");
  const std::pair<const char*, const MatrixRef*> all[] = {{"A", &A}, {"B", &B}, {"Q", &Q}, {"R", &R}};
  for (const auto& [name, M] : all)
    if (!M->allFinite()) fail(std::string(name) + " has a non-finite entry (NaN or Inf)");
}

// Relative to the matrix itself: weights that differ by 1e7 within one matrix are normal here.
void check_symmetric(const char* name, const MatrixRef& M) {
  const double asymmetry = (M - M.transpose()).norm();
  if (asymmetry > 1e-10 * M.norm())
    fail(std::string(name) + " is not symmetric (‖" + name + " − " + name + "'‖_F = " + num(asymmetry) +
         ", ‖" + name + "‖_F = " + num(M.norm()) + ")");
}

// Smallest and largest eigenvalue of a symmetric matrix. Weights are usually diagonal, and the
// per-step SDRE calls this every control step: a diagonal needs no eigensolver.
std::pair<double, double> spectrum_range(const MatrixXd& M) {
  if (M.isDiagonal(0.0)) return {M.diagonal().minCoeff(), M.diagonal().maxCoeff()};
  const Eigen::VectorXd eigenvalues = M.selfadjointView<Eigen::Lower>().eigenvalues();
  return {eigenvalues(0), eigenvalues(eigenvalues.size() - 1)};
}

// What both solvers derive from (B, Q, R) once the preconditions hold. G = B R⁻¹ B' is kept
// factored as W'W with W = L⁻¹B' (R = LL'): G·P then costs 2mn² instead of n³, P G P = (WP)'(WP)
// is exactly symmetric, and K = R⁻¹B'P = L'⁻¹(WP).
struct Weights {
  MatrixXd Q;  // symmetrized
  MatrixXd L;  // lower Cholesky factor of R
  MatrixXd W;  // L⁻¹ B', m×n
};

Weights prepare_weights(const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R) {
  check_symmetric("Q", Q);
  check_symmetric("R", R);
  Weights w;
  w.Q = 0.5 * (Q + Q.transpose());
  const auto [q_min, q_max] = spectrum_range(w.Q);
  const double q_scale = std::max(std::abs(q_min), std::abs(q_max));
  if (q_min < -100.0 * static_cast<double>(Q.rows()) * kEps * q_scale)
    fail("Q is not positive semi-definite (min eigenvalue " + num(q_min) + ", max " + num(q_max) + ")");

  const MatrixXd R_sym = 0.5 * (R + R.transpose());
  const auto [r_min, r_max] = spectrum_range(R_sym);
  // Below m·eps·max the Cholesky factor, hence G, carries no correct digit.
  if (!(r_min > static_cast<double>(R.rows()) * kEps * r_max))
    fail("R is not symmetric positive definite (min eigenvalue " + num(r_min) + ", max " + num(r_max) + ")");
  Eigen::LLT<MatrixXd> llt(R_sym);
  w.L = llt.matrixL();
  w.W = B.transpose();
  w.L.triangularView<Eigen::Lower>().solveInPlace(w.W);
  return w;
}

// Res = A'P + PA − P G P + Q for symmetric P, with WP = W·P given.
void care_residual(const MatrixRef& A, const Weights& w, const MatrixXd& P, const MatrixXd& WP, MatrixXd& Res) {
  Res.noalias() = A.transpose() * P;
  Res += Res.transpose().eval();
  Res.noalias() -= WP.transpose() * WP;
  Res += w.Q;
}

double relative_to_q(double residual_norm, const Weights& w) { return residual_norm / std::max(1.0, w.Q.norm()); }

// What a solver already knows about its P when it finishes: W·P always; the residual and the
// closed-loop spectrum when it computed them on the way (null: compute them here).
struct Solution {
  MatrixXd P;  // symmetric
  MatrixXd WP;
  const MatrixXd* residual = nullptr;
  const Eigen::VectorXcd* closed_loop_eigenvalues = nullptr;
};

// Fills K, the closed-loop spectrum and the residual, and refuses a P that does not stabilize:
// the last line of defence against returning garbage.
CareResult finish(const MatrixRef& A, const MatrixRef& B, const Weights& w, Solution s, int iterations) {
  CareResult result;
  result.K = w.L.transpose().triangularView<Eigen::Upper>().solve(s.WP);
  if (s.closed_loop_eigenvalues) {
    result.closed_loop_eigenvalues = *s.closed_loop_eigenvalues;
  } else {
    MatrixXd Ac = A;
    Ac.noalias() -= B * result.K;
    result.closed_loop_eigenvalues = Eigen::EigenSolver<MatrixXd>(Ac, false).eigenvalues();
  }
  const double max_real = result.closed_loop_eigenvalues.real().maxCoeff();
  if (!(max_real < 0.0))
    fail("the solution is not stabilizing: A − BK has an eigenvalue with Re λ = " + num(max_real) +
         kStabilizabilityHint);
  if (s.residual) {
    result.relative_residual = relative_to_q(s.residual->norm(), w);
  } else {
    MatrixXd Res(s.P.rows(), s.P.cols());
    care_residual(A, w, s.P, s.WP, Res);
    result.relative_residual = relative_to_q(Res.norm(), w);
  }
  result.P = std::move(s.P);
  result.iterations = iterations;
  return result;
}

lapack_logical is_stable(const double* re, const double* /*im*/) { return *re < 0.0; }

}  // namespace

CareResult solve_care(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R) {
  check_inputs(A, B, Q, R);
  const Weights w = prepare_weights(B, Q, R);
  const Index n = A.rows();
  const lapack_int n2 = static_cast<lapack_int>(2 * n);

  MatrixXd H(2 * n, 2 * n);
  MatrixXd U(2 * n, 2 * n);
  H.topLeftCorner(n, n) = A;
  H.topRightCorner(n, n).noalias() = -w.W.transpose() * w.W;
  H.bottomLeftCorner(n, n) = -w.Q;
  H.bottomRightCorner(n, n) = -A.transpose();

  const double g_norm = H.topRightCorner(n, n).norm();

  // Scaling only (no permutation), H_bal = D⁻¹ H D: weights spanning 1e0…1e7 make H badly
  // scaled, and on the helicopter plant the unbalanced solution was off by 1.8e-5. D is computed
  // on H without its diagonal, as scipy does: LAPACK ≥ 3.5 dgebal counts the diagonal in its
  // norms, and the large diagonal of A and −A' then hides the imbalance of G and Q (CAREX 2.1
  // went from 2e-5 to 1e-16 relative error, 2.7 from 1e-3 to 1e-10).
  MatrixXd& M = U;  // U is free until dgees writes the Schur vectors
  M = H;
  M.diagonal().setZero();
  Eigen::VectorXd d(2 * n);
  lapack_int ilo = 0;
  lapack_int ihi = 0;
  if (LAPACKE_dgebal(LAPACK_COL_MAJOR, 'S', n2, M.data(), n2, &ilo, &ihi, d.data()) != 0)
    fail("balancing the Hamiltonian failed (LAPACK dgebal)");
  H = d.cwiseInverse().asDiagonal() * H * d.asDiagonal();
  const double h_norm = H.norm();

  Eigen::VectorXd wr(2 * n);
  Eigen::VectorXd wi(2 * n);
  lapack_int stable_count = 0;
  const lapack_int info = LAPACKE_dgees(LAPACK_COL_MAJOR, 'V', 'S', is_stable, n2, H.data(), n2, &stable_count,
                                        wr.data(), wi.data(), U.data(), n2);
  if (info < 0 || (info > 0 && info <= n2))
    fail("the Schur decomposition of the Hamiltonian failed (LAPACK dgees info " + std::to_string(info) + ")");

  // A well-conditioned eigenvalue is computed to about eps·‖H_bal‖; within a few times that of
  // the axis the sign of Re λ means nothing. Larger would reject solvable problems: CAREX 2.8 has
  // a genuine Hamiltonian eigenvalue at Re λ = 5e-13 = 3.6e2·eps·‖H_bal‖.
  Index closest = 0;
  wr.cwiseAbs().minCoeff(&closest);
  const double min_abs_real = std::abs(wr(closest));
  const double axis_tolerance = 10.0 * static_cast<double>(n2) * kEps * h_norm;
  if (min_abs_real <= axis_tolerance || info == n2 + 2)
    fail("the Hamiltonian has eigenvalues on the imaginary axis (|Re λ| = " + num(min_abs_real) + " at λ = " +
         num(wr(closest)) + (wi(closest) >= 0 ? "+" : "") + num(wi(closest)) + "i, tolerance " +
         num(axis_tolerance) + ")" + kStabilizabilityHint);
  if (info == n2 + 1)
    fail("the stable eigenvalues of the Hamiltonian could not be reordered (LAPACK dgees: eigenvalues too "
         "close, the problem is too ill-conditioned)");
  if (stable_count != n)
    fail("no stabilizing solution: the Hamiltonian has " + std::to_string(stable_count) +
         " eigenvalues with Re λ < 0, " + std::to_string(n) + " needed (min |Re λ| = " + num(min_abs_real) +
         ")" + kStabilizabilityHint);

  // The balanced basis [U1; U2] is orthonormal, so rcond(U1) measures how far the stable
  // subspace is from a graph subspace; the basis of H's subspace is D·U, so
  // P = D2 U2 U1⁻¹ D1⁻¹.
  const Eigen::PartialPivLU<MatrixXd> lu(U.topLeftCorner(n, n).transpose());
  const double rcond = lu.rcond();
  if (!(rcond >= kEps))
    fail("no stabilizing solution: U1 of the stable invariant subspace [U1; U2] is singular to working "
         "precision (rcond(U1) = " + num(rcond) + ")" + kStabilizabilityHint);
  MatrixXd P = lu.solve(U.bottomLeftCorner(n, n).transpose()).transpose();
  P = d.tail(n).asDiagonal() * P * d.head(n).cwiseInverse().asDiagonal();
  P = 0.5 * (P + P.transpose()).eval();

  // Newton refinement only when the Schur solution is not backward stable, measured by the
  // normwise residual η = ‖Res‖_F / (‖Q‖_F + 2‖A‖_F‖P‖_F + ‖G‖_F‖P‖_F²). Measured: η is at rounding level on
  // the helicopter plant, CAREX 1.x–4.1 and random systems, and one Newton step there gains
  // nothing and can cost forward accuracy (CAREX 2.4: 3e-11 → 1.4e-9 relative error); on the
  // badly scaled CAREX 2.6, η = 2.4e-4 and two steps bring the error from 9e-4 to 1e-12.
  const double a_norm = A.norm();
  auto backward_error = [&](const MatrixXd& X, const MatrixXd& Res) {
    const double x_norm = X.norm();
    return Res.norm() / (w.Q.norm() + 2.0 * a_norm * x_norm + g_norm * x_norm * x_norm);
  };
  MatrixXd WP = w.W * P;
  MatrixXd Res(n, n);
  care_residual(A, w, P, WP, Res);
  double eta = backward_error(P, Res);
  int refinements = 0;
  constexpr double kRefineAbove = 1e-12;
  constexpr int kMaxRefinements = 4;
  while (eta > kRefineAbove && refinements < kMaxRefinements) {
    MatrixXd Ak = A;
    Ak.noalias() -= w.W.transpose() * WP;
    MatrixXd refined;
    try {
      refined = P + solve_lyapunov(Ak, Res);
    } catch (const Error&) {
      break;  // A − GP is not Hurwitz: finish() reports that with the eigenvalue
    }
    refined = 0.5 * (refined + refined.transpose()).eval();
    const MatrixXd refined_WP = w.W * refined;
    MatrixXd refined_Res(n, n);
    care_residual(A, w, refined, refined_WP, refined_Res);
    const double refined_eta = backward_error(refined, refined_Res);
    if (!(refined_eta < eta)) break;
    P = std::move(refined);
    WP = refined_WP;
    Res = std::move(refined_Res);
    eta = refined_eta;
    ++refinements;
  }
  // eig(A − GP) are the stable eigenvalues of H for the P of its stable subspace: the Schur form
  // has them (dgees ordered them first), which saves an eigensolver on the SDRE's hot path. A
  // refined P is no longer that P exactly, so its spectrum is computed afresh.
  Eigen::VectorXcd stable(n);
  for (Index i = 0; i < n; ++i) stable(i) = {wr(i), wi(i)};
  return finish(A, B, w, {std::move(P), std::move(WP), &Res, refinements == 0 ? &stable : nullptr}, refinements);
}

CareResult solve_care_newton(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R,
                             const MatrixRef& P0, double tolerance, int max_iterations) {
  check_inputs(A, B, Q, R);
  if (P0.rows() != A.rows() || P0.cols() != A.cols()) fail("P0 is " + shape(P0) + " but A is " + shape(A));
  if (!P0.allFinite()) fail("P0 has a non-finite entry (NaN or Inf)");
  if (!(tolerance > 0.0) || max_iterations < 1)
    fail("Newton–Kleinman needs tolerance > 0 and max_iterations ≥ 1 (got " + num(tolerance) + ", " +
         std::to_string(max_iterations) + ")");
  const Weights w = prepare_weights(B, Q, R);
  const Index n = A.rows();

  MatrixXd P = 0.5 * (P0 + P0.transpose());
  MatrixXd WP = w.W * P;
  MatrixXd Ak = A;
  Ak.noalias() -= w.W.transpose() * WP;
  const double max_real = Eigen::EigenSolver<MatrixXd>(Ak, false).eigenvalues().real().maxCoeff();
  if (!(max_real < 0.0))
    fail("Newton–Kleinman: P0 is not stabilizing (largest Re λ of A − G P0 is " + num(max_real) + ")");

  // Each step solves for the correction Δ = Pk+1 − Pk, Ak'Δ + ΔAk + Res(Pk) = 0, which is the
  // same equation as the one for Pk+1 but keeps the digits of Pk that are already right.
  MatrixXd Res(n, n);
  double residual = 0.0;
  double step = 0.0;
  int iterations = 0;
  for (;;) {
    care_residual(A, w, P, WP, Res);
    residual = relative_to_q(Res.norm(), w);
    if (residual <= tolerance) break;
    if (iterations == max_iterations)
      fail("Newton–Kleinman did not converge in " + std::to_string(iterations) + " iterations (relative residual " +
           num(residual) + ", last relative step " + num(step) + ", tolerance " + num(tolerance) + ")");
    MatrixXd delta;
    try {
      delta = solve_lyapunov(Ak, Res);
    } catch (const Error& e) {
      fail("Newton–Kleinman step " + std::to_string(iterations + 1) + ": " + e.what());
    }
    P += delta;
    P = 0.5 * (P + P.transpose()).eval();
    ++iterations;
    WP.noalias() = w.W * P;
    Ak = A;
    Ak.noalias() -= w.W.transpose() * WP;
    step = delta.norm() / std::max(1.0, P.norm());
    // Rounding limits the residual of an ill-conditioned equation long before the step stalls.
    if (step <= tolerance) break;
  }
  // Res belongs to P only when the loop stopped on the residual; after a step it is stale.
  const bool residual_current = residual <= tolerance;
  return finish(A, B, w, {std::move(P), std::move(WP), residual_current ? &Res : nullptr, nullptr}, iterations);
}

}  // namespace thetad
