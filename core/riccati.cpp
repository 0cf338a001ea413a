#include "core/riccati.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/care_diagnosis.hpp"
#include "core/care_solver_workspace.hpp"
#include "core/care_refinement.hpp"
#include "core/care_weights.hpp"
#include "core/error.hpp"
#include "core/lapack.hpp"
#include "core/lyapunov.hpp"
#include "core/lyapunov_certificate.hpp"
#include "core/machine_epsilon.hpp"
#include "core/matrix_sign.hpp"

namespace thetad {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using care::Candidate;
using care::kRefineAbove;
using care::MatrixRef;

using care::fail;
using care::kStabilizabilityHint;
using care::num;
using care::Weights;

static_assert(sizeof(lapack_int) == sizeof(int) && sizeof(lapack_logical) == sizeof(int),
              "CareSolver stores LAPACK integers as int");

lapack_logical is_stable(const double* re, const double* /*im*/) { return *re < 0.0; }

// Scaled Newton needs 8 inversions on the paper's problem and 9–13 on random ones of its size;
// 40 is reached only near the imaginary axis, where the Schur method is the one to trust.
constexpr int kSignIterations = 40;

}  // namespace

CareSolver::Workspace::Workspace(const MatrixRef& Q, const MatrixRef& R_, CareMethod method_, StabilityProof proof_,
                                 ErrorEstimates estimates_)
    : method(method_), proof(proof_), estimates(estimates_), R(R_), n(Q.rows()), m(R_.rows()), H(2 * n, 2 * n),
      H_s(2 * n, 2 * n), d(2 * n), d_balance(2 * n), sign(2 * n), lhs(2 * n, n), rhs(2 * n, n), qr_coefficients(n), qr_workspace(n),
      U(2 * n, 2 * n), U1(n, n), X(n, n), wr(2 * n), wi(2 * n), lu_work(4 * n), bwork(2 * n), pivots(n), lu_iwork(n),
      Ak(n, n), delta(n, n), refinement(std::max<Index>(n, 1), std::max<Index>(m, 1)), certificate(n), eigen(n) {
  if (n == 0 || Q.cols() != n) fail("Q must be square and non-empty, but Q is " + care::shape(Q));
  if (m == 0 || R_.cols() != m) fail("R must be square and non-empty, but R is " + care::shape(R_));
  if (!Q.allFinite()) fail("Q has a non-finite entry (NaN or Inf)");
  if (!R_.allFinite()) fail("R has a non-finite entry (NaN or Inf)");
  w = care::prepare_weights(Q, R_);
  w.W.resize(m, n);
  for (Candidate* c : {&candidate, &next}) {
    c->P.resize(n, n);
    c->WP.resize(m, n);
    c->Res.resize(n, n);
  }
  // dgees' optimal workspace (a query), so that the blocked Hessenberg reduction can run.
  const auto n2 = static_cast<lapack_int>(2 * n);
  double optimal = 0.0;
  lapack_int sdim = 0;
  if (LAPACKE_dgees_work(LAPACK_COL_MAJOR, 'V', 'S', is_stable, n2, H.data(), n2, &sdim, wr.data(), wi.data(),
                         U.data(), n2, &optimal, -1, bwork.data()) != 0)
    fail("the dgees workspace query failed");
  schur_work.resize(std::max<Index>(static_cast<Index>(optimal), 3 * n2));
  result.P.resize(n, n);
  result.K.resize(m, n);
  result.closed_loop_eigenvalues.resize(n);
}

void CareSolver::Workspace::form_hamiltonian(const MatrixRef& A) {
  H.topLeftCorner(n, n) = A;
  H.topRightCorner(n, n).noalias() = -w.W.transpose() * w.W;
  H.bottomLeftCorner(n, n) = -w.Q;
  H.bottomRightCorner(n, n) = -A.transpose();
  g_norm = care::frobenius_norm(H.topRightCorner(n, n));
}

void CareSolver::Workspace::scale_hamiltonian() {
  for (Index j = 0; j < 2 * n; ++j)
    for (Index i = 0; i < 2 * n; ++i) H_s(i, j) = 1.0 / d(i) * H(i, j) * d(j);
}

// For the sign function, one scalar that gives G and Q the same 1-norm, as SB02MD's SCAL = 'G'
// (D = diag(I, sI) keeps H Hamiltonian). Measured against 40-digit reference solutions (see
// docs/riccati.md): with it the sign function's forward error on the paper problem is
// ~1e-15 and on random paper-scaled problems on a par with SB02MD; with the Schur method's
// balancing instead it was larger on 9 of those 13 problems (1.4× in geometric mean).
void CareSolver::Workspace::equilibrate() {
  const double q_norm = H.bottomLeftCorner(n, n).cwiseAbs().colwise().sum().maxCoeff();
  const double g_1norm = H.topRightCorner(n, n).cwiseAbs().colwise().sum().maxCoeff();
  d.setOnes();
  // The square roots apart: q_norm / g_1norm overflows or underflows for weights scaled by 1e±170.
  if (q_norm > 0.0 && g_1norm > 0.0) d.tail(n).setConstant(std::sqrt(q_norm) / std::sqrt(g_1norm));
  scale_hamiltonian();
}

// For the Schur method, balancing only (no permutation): weights spanning 1e0…1e7 make H badly
// scaled, and on the helicopter plant the unbalanced Schur solution was off by 1.8e-5. D is
// computed on H without its diagonal, as scipy does: LAPACK ≥ 3.5 dgebal counts the diagonal in
// its norms, and the large diagonal of A and −A' then hides the imbalance of G and Q (CAREX 2.1
// went from 2e-5 to 1e-16 relative error, 2.7 from 1e-3 to 1e-10). dgebal starts from the
// equilibrated H: alone, it left weights scaled by 1e50 (Q·s, R·s, hence P·s) with a balanced H
// of norm 5e18 and refused them as having eigenvalues on the imaginary axis; from the
// equilibrated H, whose blocks do not depend on s, the paper's problem is solved to 3e-15 from
// s = 1e-300 to 1e300, and the accuracy on random problems stayed where it was (docs/riccati.md).
void CareSolver::Workspace::balance() {
  const auto n2 = static_cast<lapack_int>(2 * n);
  equilibrate();
  H_s.diagonal().setZero();
  lapack_int ilo = 0;
  lapack_int ihi = 0;
  if (LAPACKE_dgebal_work(LAPACK_COL_MAJOR, 'S', n2, H_s.data(), n2, &ilo, &ihi, d_balance.data()) != 0)
    fail("balancing the Hamiltonian failed (LAPACK dgebal)");
  d.array() *= d_balance.array();
  scale_hamiltonian();
}

// P = D2 P_s D1⁻¹, symmetrized.
void CareSolver::Workspace::unscale(const Eigen::Ref<const MatrixXd>& P_s, MatrixXd& P) const {
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) P(i, j) = d(n + i) * P_s(i, j) * (1.0 / d(j));
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < j; ++i) P(i, j) = P(j, i) = 0.5 * (P(i, j) + P(j, i));
}

// The stable invariant subspace [I; P] of H is the null space of sign(H) + I:
// [S12; S22 + I] P = −[S11 + I; S21], 2n consistent equations for n columns, solved by QR.
// False when the iteration fails or the system has no unique solution (no stabilizing P): the
// Schur method then says which. The solution goes to candidate.P.
bool CareSolver::Workspace::sign_solution(int& iterations) {
  equilibrate();
  const std::optional<int> inversions = sign.compute(H_s, kSignIterations);
  if (!inversions) return false;
  iterations = *inversions;
  const MatrixXd& S = sign.sign();
  lhs.topRows(n) = S.topRightCorner(n, n);
  lhs.bottomRows(n) = S.bottomRightCorner(n, n);
  lhs.bottomRows(n).diagonal().array() += 1.0;
  rhs.topRows(n) = -S.topLeftCorner(n, n);
  rhs.topRows(n).diagonal().array() -= 1.0;
  rhs.bottomRows(n) = -S.bottomLeftCorner(n, n);
  // Householder QR and its least-squares solve, as HouseholderQR::compute and ::solve, into the
  // buffers of this object: one reflector at a time, because Eigen's blocked forms allocate from
  // n = 48 on (below that its compute() is this unblocked one).
  Eigen::internal::householder_qr_inplace_unblocked(lhs, qr_coefficients, qr_workspace.data());
  const auto r_diagonal = lhs.diagonal().cwiseAbs();
  if (!(r_diagonal.minCoeff() > static_cast<double>(2 * n) * kEps * r_diagonal.maxCoeff())) return false;
  for (Index k = 0; k < n; ++k)
    rhs.bottomRows(2 * n - k).applyHouseholderOnTheLeft(lhs.col(k).tail(2 * n - k - 1), qr_coefficients(k),
                                                        qr_workspace.data());
  lhs.topLeftCorner(n, n).triangularView<Eigen::Upper>().solveInPlace(rhs.topRows(n));
  if (!rhs.topRows(n).allFinite()) return false;
  unscale(rhs.topRows(n), candidate.P);
  return true;
}

// Laub's method on the balanced H; throws with the reason when there is no stabilizing solution.
// The solution goes to candidate.P; the stable eigenvalues of H, which are eig(A − GP), to wr, wi.
void CareSolver::Workspace::schur_solution() {
  balance();
  const auto n2 = static_cast<lapack_int>(2 * n);
  const auto n1 = static_cast<lapack_int>(n);
  const double h_norm = care::frobenius_norm(H_s);
  lapack_int stable_count = 0;
  const lapack_int info = LAPACKE_dgees_work(LAPACK_COL_MAJOR, 'V', 'S', is_stable, n2, H_s.data(), n2,
                                             &stable_count, wr.data(), wi.data(), U.data(), n2, schur_work.data(),
                                             static_cast<lapack_int>(schur_work.size()), bwork.data());
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
  // a graph subspace; P_bal = U2 U1⁻¹, i.e. U1' P_bal' = U2'. rcond in the ∞-norm of U1, the
  // 1-norm of the U1' that is solved with.
  U1 = U.topLeftCorner(n, n);
  const double u1_norm = U1.cwiseAbs().rowwise().sum().maxCoeff();
  double rcond = 0.0;
  if (LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, n1, n1, U1.data(), n1, pivots.data()) < 0 ||
      LAPACKE_dgecon_work(LAPACK_COL_MAJOR, 'I', n1, U1.data(), n1, u1_norm, &rcond, lu_work.data(),
                          lu_iwork.data()) != 0)
    rcond = 0.0;
  if (!(rcond >= kEps))
    fail("no stabilizing solution: U1 of the stable invariant subspace [U1; U2] is singular to working "
         "precision (rcond(U1) = " + num(rcond) + ")" + kStabilizabilityHint);
  X = U.bottomLeftCorner(n, n).transpose();
  LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'T', n1, n1, U1.data(), n1, pivots.data(), X.data(), n1);
  X.transposeInPlace();
  unscale(X, candidate.P);
}

// Fills K, the closed-loop spectrum (unless wr, wi hold it already, or the Lyapunov certificate
// proves stability when asked to) and the residual, and refuses a P that does not stabilize: the
// last line of defence against returning garbage.
const CareResult& CareSolver::Workspace::finish(const MatrixRef& A, const MatrixRef& B, bool have_spectrum,
                                                int iterations) {
  // A basis of the stable subspace that is not a graph can slip past the rcond test (or come out
  // of a balancing that had nothing to balance) as Inf/NaN entries: never return those.
  if (!candidate.P.allFinite() || !candidate.WP.allFinite())
    fail("no stabilizing solution: the computed P has non-finite entries" + std::string(kStabilizabilityHint));
  result.K = candidate.WP;
  w.L.transpose().triangularView<Eigen::Upper>().solveInPlace(result.K);
  const bool certified = !have_spectrum && proof == StabilityProof::lyapunov &&
                         certificate.proves_hurwitz(A, w, candidate.P, candidate.WP, candidate.Res);
  if (certified) {
    leave_spectrum_uncomputed(result);
  } else {
    if (have_spectrum) {
      for (Index i = 0; i < n; ++i) result.closed_loop_eigenvalues(i) = {wr(i), wi(i)};
    } else {
      Ak = A;
      Ak.noalias() -= B * result.K;
      eigen.compute(Ak, false);
      result.closed_loop_eigenvalues = eigen.eigenvalues();
    }
    const double max_real = result.closed_loop_eigenvalues.real().maxCoeff();
    if (!(max_real < 0.0))
      fail("the solution is not stabilizing: A − BK has an eigenvalue with Re λ = " + num(max_real) +
           kStabilizabilityHint);
  }
  result.relative_residual = care::relative_to_q(care::frobenius_norm(candidate.Res), w);
  result.P = candidate.P;
  result.iterations = iterations;
  return result;
}

const CareResult& CareSolver::Workspace::solve(const MatrixRef& A, const MatrixRef& B) {
  care::check_inputs(A, B, w.Q, R);
  closed_loop_balanced = closed_loop_factored = false;
  known_forward_error = std::numeric_limits<double>::quiet_NaN();
  care::set_input_matrix(w, B);
  form_hamiltonian(A);

  if (method != CareMethod::schur) {
    int sign_iterations = 0;
    if (sign_solution(sign_iterations)) {
      evaluate(A, candidate);
      if (candidate.eta <= kRefineAbove || method == CareMethod::matrix_sign) {
        const int refinements = refine(A);
        if (candidate.eta > kRefineAbove)
          fail("the matrix sign solution is not backward stable (normwise residual " + num(candidate.eta) +
               " after " + std::to_string(refinements) + " Newton refinement steps); CareMethod::schur or "
               "automatic solves this equation");
        const int steps = method == CareMethod::automatic && terms_dwarf_q(A) ? compensated_steps(A, B) : 0;
        finish(A, B, false, refinements + steps);
        result.sign_iterations = sign_iterations;
        if (estimates == ErrorEstimates::on) estimate_errors(A, B);
        return result;
      }
    } else if (method == CareMethod::matrix_sign) {
      fail("the matrix sign iteration on the Hamiltonian failed (a singular iterate, no convergence in " +
           std::to_string(kSignIterations) + " inversions, or no unique P; CareMethod::schur says which)" +
           kStabilizabilityHint);
    }
  }

  schur_solution();
  evaluate(A, candidate);
  int refinements = refine(A);
  if (method == CareMethod::automatic && terms_dwarf_q(A)) refinements += compensated_steps(A, B);
  // eig(A − GP) are the stable eigenvalues of H for the P of its stable subspace: the Schur form
  // has them (dgees ordered them first), which saves an eigensolver. A refined P is no longer that
  // P exactly, so its spectrum is computed afresh.
  finish(A, B, refinements == 0, refinements);
  result.sign_iterations = 0;
  if (estimates == ErrorEstimates::on) estimate_errors(A, B);
  return result;
}

CareSolver::CareSolver(const MatrixRef& Q, const MatrixRef& R, CareMethod method, StabilityProof proof,
                       ErrorEstimates estimates)
    : workspace_(std::make_unique<Workspace>(Q, R, method, proof, estimates)) {}

CareSolver::~CareSolver() = default;

CareSolver::CareSolver(const CareSolver& other) : workspace_(std::make_unique<Workspace>(*other.workspace_)) {}

const CareResult& CareSolver::solve(const MatrixRef& A, const MatrixRef& B) {
  try {
    return workspace_->solve(A, B);
  } catch (const Error& error) {
    rethrow_with_diagnosis(error, A, B, workspace_->w.Q);
  }
}

CareResult solve_care(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R,
                      CareMethod method, ErrorEstimates estimates) {
  care::check_inputs(A, B, Q, R);
  return CareSolver(Q, R, method, StabilityProof::spectrum, estimates).solve(A, B);
}

CareResult solve_care(const MatrixRef& A, const MatrixRef& B, const MatrixRef& Q, const MatrixRef& R,
                      const MatrixRef& N, CareMethod method, ErrorEstimates estimates) {
  care::check_inputs(A, B, Q, R);
  care::check_cross_term("N", N, B, "CARE");
  care::check_symmetric("R", R);
  const Eigen::LDLT<MatrixXd> R_factored(0.5 * (R + R.transpose()));
  if (R_factored.info() != Eigen::Success || !R_factored.isPositive() ||
      !(R_factored.rcond() > static_cast<double>(R.rows()) * kEps))
    fail("R is not symmetric positive definite (rcond(R) = " + num(R_factored.rcond()) + ")");
  const care::WithoutCrossTerm reduced = care::eliminate_cross_term(A, B, Q, N, R_factored);
  CareResult result = solve_care(reduced.A, B, reduced.Q, R, method, estimates);
  result.K += reduced.RinvSt;
  return result;
}

}  // namespace thetad
