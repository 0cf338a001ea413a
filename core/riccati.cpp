#include "core/riccati.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "core/care_diagnosis.hpp"
#include "core/care_weights.hpp"
#include "core/error.hpp"
#include "core/lapack.hpp"
#include "core/lyapunov.hpp"
#include "core/matrix_sign.hpp"

namespace thetad {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using care::MatrixRef;

using care::fail;
using care::kStabilizabilityHint;
using care::num;
using care::Weights;

constexpr double kEps = std::numeric_limits<double>::epsilon();

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
  // A basis of the stable subspace that is not a graph can slip past the rcond test (or come out
  // of a balancing that had nothing to balance) as Inf/NaN entries: never return those.
  if (!s.P.allFinite() || !s.WP.allFinite())
    fail("no stabilizing solution: the computed P has non-finite entries" + std::string(kStabilizabilityHint));
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
    result.relative_residual = care::relative_to_q(s.residual->norm(), w);
  } else {
    MatrixXd Res(s.P.rows(), s.P.cols());
    care::care_residual(A, w, s.P, s.WP, Res);
    result.relative_residual = care::relative_to_q(Res.norm(), w);
  }
  result.P = std::move(s.P);
  result.iterations = iterations;
  return result;
}

lapack_logical is_stable(const double* re, const double* /*im*/) { return *re < 0.0; }

// H = [A, −G; −Q, −A'].
MatrixXd hamiltonian(const MatrixRef& A, const Weights& w) {
  const Index n = A.rows();
  MatrixXd H(2 * n, 2 * n);
  H.topLeftCorner(n, n) = A;
  H.topRightCorner(n, n).noalias() = -w.W.transpose() * w.W;
  H.bottomLeftCorner(n, n) = -w.Q;
  H.bottomRightCorner(n, n) = -A.transpose();
  return H;
}

// A P with everything finish() and the refinement need about it.
struct Candidate {
  MatrixXd P;
  MatrixXd WP;
  MatrixXd Res;
  double eta;  // normwise backward error, see evaluate()
};

// η: care::normwise_residual.
Candidate evaluate(const MatrixRef& A, const Weights& w, double g_norm, MatrixXd P) {
  Candidate c{std::move(P), {}, MatrixXd(A.rows(), A.cols()), 0.0};
  c.WP.noalias() = w.W * c.P;
  care::care_residual(A, w, c.P, c.WP, c.Res);
  c.eta = care::normwise_residual(c.Res.norm(), w.Q.norm(), A.norm(), g_norm, c.P.norm());
  return c;
}

// Newton refinement only when a direct solution is not backward stable. Measured: η is at
// rounding level on the helicopter plant, CAREX 1.x–4.1 and random systems, and one Newton step
// there gains nothing and can cost forward accuracy (CAREX 2.4: 3e-11 → 1.4e-9 relative error);
// on the badly scaled CAREX 2.6, η = 2.4e-4 after the Schur method and two steps bring the error
// from 9e-4 to 1e-12.
constexpr double kRefineAbove = 1e-12;

// Returns the refinement steps taken; c is replaced only by better candidates.
int refine(const MatrixRef& A, const Weights& w, double g_norm, Candidate& c) {
  constexpr int kMaxRefinements = 4;
  int refinements = 0;
  while (c.eta > kRefineAbove && refinements < kMaxRefinements) {
    MatrixXd Ak = A;
    Ak.noalias() -= w.W.transpose() * c.WP;
    MatrixXd refined;
    try {
      refined = c.P + solve_lyapunov(Ak, c.Res);
    } catch (const Error&) {
      break;  // A − GP is not Hurwitz: finish() reports that with the eigenvalue
    }
    Candidate next = evaluate(A, w, g_norm, 0.5 * (refined + refined.transpose()));
    if (!(next.eta < c.eta)) break;
    c = std::move(next);
    ++refinements;
  }
  return refinements;
}

// Both direct methods work on a diagonally scaled H_s = D⁻¹ H D, D = diag(d); a basis of the
// stable subspace of H is D times one of H_s's, so [I; P_s] for H_s gives P = D2 P_s D1⁻¹.
struct ScaledHamiltonian {
  MatrixXd H;  // D⁻¹ H D
  Eigen::VectorXd d;

  MatrixXd unscale(const MatrixXd& P_s) const {
    const Index n = P_s.rows();
    const MatrixXd P = d.tail(n).asDiagonal() * P_s * d.head(n).cwiseInverse().asDiagonal();
    return 0.5 * (P + P.transpose());
  }
};

ScaledHamiltonian scaled(const MatrixXd& H, Eigen::VectorXd d) {
  return {d.cwiseInverse().asDiagonal() * H * d.asDiagonal(), std::move(d)};
}

// For the Schur method, balancing only (no permutation): weights spanning 1e0…1e7 make H badly
// scaled, and on the helicopter plant the unbalanced Schur solution was off by 1.8e-5. D is
// computed on H without its diagonal, as scipy does: LAPACK ≥ 3.5 dgebal counts the diagonal in
// its norms, and the large diagonal of A and −A' then hides the imbalance of G and Q (CAREX 2.1
// went from 2e-5 to 1e-16 relative error, 2.7 from 1e-3 to 1e-10).
ScaledHamiltonian balanced(const MatrixXd& H) {
  const lapack_int n2 = static_cast<lapack_int>(H.rows());
  MatrixXd M = H;
  M.diagonal().setZero();
  Eigen::VectorXd d(n2);
  lapack_int ilo = 0;
  lapack_int ihi = 0;
  if (LAPACKE_dgebal(LAPACK_COL_MAJOR, 'S', n2, M.data(), n2, &ilo, &ihi, d.data()) != 0)
    fail("balancing the Hamiltonian failed (LAPACK dgebal)");
  return scaled(H, std::move(d));
}

// For the sign function, one scalar that gives G and Q the same 1-norm, as SB02MD's SCAL = 'G'
// (D = diag(I, sI) keeps H Hamiltonian). Measured against 40-digit reference solutions (see
// docs/performance.md): with it the sign function's forward error on the paper problem is
// ~1e-15 and on random paper-scaled problems on a par with SB02MD; with the Schur method's
// balancing instead it was larger on 9 of those 13 problems (1.4× in geometric mean).
ScaledHamiltonian equilibrated(const MatrixXd& H) {
  const Index n = H.rows() / 2;
  const double q_norm = H.bottomLeftCorner(n, n).cwiseAbs().colwise().sum().maxCoeff();
  const double g_norm = H.topRightCorner(n, n).cwiseAbs().colwise().sum().maxCoeff();
  Eigen::VectorXd d = Eigen::VectorXd::Ones(2 * n);
  if (q_norm > 0.0 && g_norm > 0.0) d.tail(n).setConstant(std::sqrt(q_norm / g_norm));
  return scaled(H, std::move(d));
}

// Scaled Newton needs 8 inversions on the paper's problem and 9–13 on random ones of its size;
// 40 is reached only near the imaginary axis, where the Schur method is the one to trust.
constexpr int kSignIterations = 40;

// The stable invariant subspace [I; P] of H is the null space of sign(H) + I:
// [S12; S22 + I] P = −[S11 + I; S21], 2n consistent equations for n columns, solved by QR.
// Empty when the iteration fails or the system has no unique solution (no stabilizing P): the
// Schur method then says which.
std::optional<MatrixXd> sign_solution(const ScaledHamiltonian& scaled_h, int& iterations) {
  const Index n = scaled_h.H.rows() / 2;
  const std::optional<MatrixSign> sign = matrix_sign(scaled_h.H, kSignIterations);
  if (!sign) return std::nullopt;
  iterations = sign->iterations;
  const MatrixXd& S = sign->sign;
  MatrixXd lhs(2 * n, n);
  MatrixXd rhs(2 * n, n);
  lhs << S.topRightCorner(n, n), S.bottomRightCorner(n, n) + MatrixXd::Identity(n, n);
  rhs << S.topLeftCorner(n, n) + MatrixXd::Identity(n, n), S.bottomLeftCorner(n, n);
  const Eigen::HouseholderQR<MatrixXd> qr(lhs);
  const Eigen::VectorXd r_diagonal = qr.matrixQR().diagonal().cwiseAbs();
  if (!(r_diagonal.minCoeff() > static_cast<double>(2 * n) * kEps * r_diagonal.maxCoeff())) return std::nullopt;
  const MatrixXd P_s = -qr.solve(rhs);
  if (!P_s.allFinite()) return std::nullopt;
  return scaled_h.unscale(P_s);
}

// Laub's method on the balanced H; throws with the reason when there is no stabilizing solution.
// The stable eigenvalues of H, which are eig(A − GP), come back in `stable`.
MatrixXd schur_solution(const ScaledHamiltonian& scaled_h, Eigen::VectorXcd& stable) {
  MatrixXd H = scaled_h.H;
  const Index n = H.rows() / 2;
  const lapack_int n2 = static_cast<lapack_int>(2 * n);
  MatrixXd U(2 * n, 2 * n);
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

  // The basis [U1; U2] is orthonormal, so rcond(U1) measures how far the stable subspace is from
  // a graph subspace; P_bal = U2 U1⁻¹.
  const Eigen::PartialPivLU<MatrixXd> lu(U.topLeftCorner(n, n).transpose());
  const double rcond = lu.rcond();
  if (!(rcond >= kEps))
    fail("no stabilizing solution: U1 of the stable invariant subspace [U1; U2] is singular to working "
         "precision (rcond(U1) = " + num(rcond) + ")" + kStabilizabilityHint);
  stable.resize(n);
  for (Index i = 0; i < n; ++i) stable(i) = {wr(i), wi(i)};
  return scaled_h.unscale(lu.solve(U.bottomLeftCorner(n, n).transpose()).transpose());
}

CareResult solve_checked(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R,
                         CareMethod method) {
  Weights w = care::prepare_weights(Q, R);
  care::set_input_matrix(w, B);
  const Index n = A.rows();
  const MatrixXd H = hamiltonian(A, w);
  const double g_norm = H.topRightCorner(n, n).norm();

  if (method != CareMethod::schur) {
    int sign_iterations = 0;
    if (std::optional<MatrixXd> P = sign_solution(equilibrated(H), sign_iterations)) {
      Candidate c = evaluate(A, w, g_norm, std::move(*P));
      if (c.eta <= kRefineAbove || method == CareMethod::matrix_sign) {
        const int refinements = refine(A, w, g_norm, c);
        if (c.eta > kRefineAbove)
          fail("the matrix sign solution is not backward stable (normwise residual " + num(c.eta) + " after " +
               std::to_string(refinements) + " Newton refinement steps); CareMethod::schur or automatic solves "
               "this equation");
        CareResult result = finish(A, B, w, {std::move(c.P), std::move(c.WP), &c.Res, nullptr}, refinements);
        result.sign_iterations = sign_iterations;
        return result;
      }
    } else if (method == CareMethod::matrix_sign) {
      fail("the matrix sign iteration on the Hamiltonian failed (a singular iterate, no convergence in " +
           std::to_string(kSignIterations) + " inversions, or no unique P; CareMethod::schur says which)" +
           kStabilizabilityHint);
    }
  }

  Eigen::VectorXcd stable;
  Candidate c = evaluate(A, w, g_norm, schur_solution(balanced(H), stable));
  const int refinements = refine(A, w, g_norm, c);
  // eig(A − GP) are the stable eigenvalues of H for the P of its stable subspace: the Schur form
  // has them (dgees ordered them first), which saves an eigensolver. A
  // refined P is no longer that P exactly, so its spectrum is computed afresh.
  return finish(A, B, w, {std::move(c.P), std::move(c.WP), &c.Res, refinements == 0 ? &stable : nullptr},
                refinements);
}

}  // namespace

CareResult solve_care(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R,
                      CareMethod method) {
  care::check_inputs(A, B, Q, R);
  try {
    return solve_checked(A, B, Q, R, method);
  } catch (const Error& error) {
    rethrow_with_diagnosis(error, A, B, Q);
  }
}

}  // namespace thetad
