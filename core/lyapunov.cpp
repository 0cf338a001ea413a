#include "core/lyapunov.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "core/error.hpp"
#include "core/lapack.hpp"

namespace thetad {
namespace {

std::string shape(const Eigen::Ref<const Eigen::MatrixXd>& M) {
  return std::to_string(M.rows()) + "x" + std::to_string(M.cols());
}

}  // namespace

Eigen::MatrixXd solve_lyapunov(const Eigen::Ref<const Eigen::MatrixXd>& A,
                               const Eigen::Ref<const Eigen::MatrixXd>& Q) {
  if (A.rows() != A.cols()) throw Error("solve_lyapunov: A must be square, got " + shape(A));
  if (Q.rows() != A.rows() || Q.cols() != A.cols())
    throw Error("solve_lyapunov: Q must have the size of A (" + shape(A) + "), got " + shape(Q));
  if (!Q.allFinite()) throw Error("solve_lyapunov: Q has non-finite entries");
  if (A.rows() == 0) return Eigen::MatrixXd(0, 0);
  LyapunovWorkspace workspace(A.rows());
  workspace.factor(A);
  Eigen::MatrixXd X(A.rows(), A.cols());
  workspace.solve(Q, X);
  return X;
}

static_assert(sizeof(lapack_int) == sizeof(int) && sizeof(lapack_logical) == sizeof(int),
              "LyapunovWorkspace stores LAPACK integers as int");

LyapunovWorkspace::LyapunovWorkspace(Eigen::Index n)
    : n_(static_cast<int>(n)), T_(n, n), U_(n, n), Y_(n, n), scratch_(n, n), wr_(n), wi_(n), bwork_(n) {
  if (n < 1) throw Error("LyapunovWorkspace: n must be at least 1, got " + std::to_string(n));
  // dgees' optimal workspace (a query), so that the blocked Hessenberg reduction can run.
  double optimal = 0.0;
  lapack_int sdim = 0;
  const lapack_int info = LAPACKE_dgees_work(LAPACK_COL_MAJOR, 'V', 'N', nullptr, n_, T_.data(), n_, &sdim,
                                             wr_.data(), wi_.data(), U_.data(), n_, &optimal, -1, bwork_.data());
  if (info != 0) throw Error("LyapunovWorkspace: dgees workspace query failed (info " + std::to_string(info) + ")");
  work_.resize(std::max<Eigen::Index>(static_cast<Eigen::Index>(optimal), 3 * n));
}

void LyapunovWorkspace::schur(const Eigen::Ref<const Eigen::MatrixXd>& A, char vectors) {
  if (A.rows() != n_ || A.cols() != n_)
    throw Error("solve_lyapunov: A must be " + std::to_string(n_) + "x" + std::to_string(n_) + ", got " + shape(A));
  if (!A.allFinite()) throw Error("solve_lyapunov: A has non-finite entries");
  T_ = A;
  a_norm_ = A.norm();
  lapack_int sdim = 0;
  const lapack_int info =
      LAPACKE_dgees_work(LAPACK_COL_MAJOR, vectors, 'N', nullptr, n_, T_.data(), n_, &sdim, wr_.data(), wi_.data(),
                         U_.data(), n_, work_.data(), static_cast<lapack_int>(work_.size()), bwork_.data());
  if (info != 0)
    throw Error("solve_lyapunov: the real Schur form of A did not converge (dgees info " + std::to_string(info) + ")");
  factored_ = vectors == 'V';
}

void LyapunovWorkspace::factor(const Eigen::Ref<const Eigen::MatrixXd>& A) { schur(A, 'V'); }

void LyapunovWorkspace::compute_eigenvalues(const Eigen::Ref<const Eigen::MatrixXd>& A) { schur(A, 'N'); }

void LyapunovWorkspace::solve(const Eigen::Ref<const Eigen::MatrixXd>& Q, Eigen::Ref<Eigen::MatrixXd> X) {
  if (!factored_) throw Error("LyapunovWorkspace::solve: factor(A) first");
  if (Q.rows() != n_ || Q.cols() != n_ || X.rows() != n_ || X.cols() != n_)
    throw Error("solve_lyapunov: Q and X must be " + std::to_string(n_) + "x" + std::to_string(n_) + ", got Q " +
                shape(Q) + " and X " + std::to_string(X.rows()) + "x" + std::to_string(X.cols()));

  // The operator's eigenvalues are λi + λj; checking them here gives a message that names the
  // cause instead of dtrsyl's silent perturbation. Squared moduli: no hypot in the O(n²) loop.
  double smallest_squared = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n_; ++j)
    for (int i = j; i < n_; ++i) {
      const double re = wr_(i) + wr_(j);
      const double im = wi_(i) + wi_(j);
      smallest_squared = std::min(smallest_squared, re * re + im * im);
    }
  const double smallest = std::sqrt(smallest_squared);
  const double threshold = 1e-10 * std::max(a_norm_, 1.0);
  if (smallest <= threshold) {
    std::ostringstream message;
    message << "solve_lyapunov: the Lyapunov operator X -> A'X + XA is singular to working "
               "precision: min |λi(A) + λj(A)| = "
            << smallest << " <= " << threshold
            << " (A and -A share an eigenvalue, e.g. an eigenvalue on the imaginary axis)";
    throw Error(message.str());
  }

  // A = U T U' turns A'X + XA = −Q into T'Y + YT = −U'QU, Y = U'XU.
  scratch_.noalias() = U_.transpose() * Q;
  Y_.noalias() = -scratch_ * U_;
  double scale = 1.0;
  const lapack_int info =
      LAPACKE_dtrsyl_work(LAPACK_COL_MAJOR, 'T', 'N', 1, n_, n_, T_.data(), n_, T_.data(), n_, Y_.data(), n_, &scale);
  if (info < 0) throw Error("solve_lyapunov: dtrsyl rejected argument " + std::to_string(-info));
  if (info == 1)
    throw Error("solve_lyapunov: A and -A have nearly equal eigenvalues; dtrsyl had to perturb "
                "them (min |λi + λj| = " + std::to_string(smallest) + ")");
  scratch_.noalias() = U_ * Y_;
  X.noalias() = scratch_ * U_.transpose();
  // scale < 1 only when dtrsyl scaled the right side down to avoid overflow.
  if (scale != 1.0) X /= scale;
  if (!X.allFinite())
    throw Error("solve_lyapunov: the solution overflowed (dtrsyl scale " + std::to_string(scale) + ")");
  if (Q == Q.transpose())
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < j; ++i) X(i, j) = X(j, i) = 0.5 * (X(i, j) + X(j, i));
}

ConstantLyapunovSolver::ConstantLyapunovSolver(const Eigen::Ref<const Eigen::MatrixXd>& Ac)
    : n_(Ac.rows()) {
  if (Ac.rows() != Ac.cols())
    throw Error("ConstantLyapunovSolver: Ac must be square, got " + shape(Ac));
  if (n_ == 0) throw Error("ConstantLyapunovSolver: Ac is empty");
  if (!Ac.allFinite()) throw Error("ConstantLyapunovSolver: Ac has non-finite entries");

  max_real_eigenvalue_ = Eigen::EigenSolver<Eigen::MatrixXd>(Ac, false).eigenvalues().real().maxCoeff();
  if (!(max_real_eigenvalue_ < 0.0)) {
    std::ostringstream message;
    message << "ConstantLyapunovSolver: Ac is not Hurwitz (max Re λ(Ac) = " << max_real_eigenvalue_
            << " >= 0); the Lyapunov equation has no unique solution";
    throw Error(message.str());
  }

  // Column (k, l) of the packed operator is L(E) = Ac'E + E Ac for the symmetric unit matrix
  // E = e_k e_l' + e_l e_k', read on the upper triangle. L(e_a e_b') adds row a of Ac (as a
  // column) to column b, and row b of Ac to row a.
  const Eigen::Index m = n_ * (n_ + 1) / 2;
  Eigen::MatrixXd op(m, m);
  Eigen::MatrixXd image(n_, n_);
  auto add_unit_image = [&](Eigen::Index a, Eigen::Index b) {
    image.col(b) += Ac.row(a).transpose();
    image.row(a) += Ac.row(b);
  };
  for (Eigen::Index l = 0; l < n_; ++l) {
    for (Eigen::Index k = 0; k <= l; ++k) {
      image.setZero();
      add_unit_image(k, l);
      if (k != l) add_unit_image(l, k);
      const Eigen::Index column = packed_index(k, l);
      for (Eigen::Index j = 0; j < n_; ++j)
        for (Eigen::Index i = 0; i <= j; ++i) op(packed_index(i, j), column) = image(i, j);
    }
  }

  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(op);
  inverse_ = -lu.inverse();
  const double op_norm = op.cwiseAbs().colwise().sum().maxCoeff();
  condition_number_ = op_norm * inverse_.cwiseAbs().colwise().sum().maxCoeff();
  if (!(condition_number_ <= 1e14)) {
    std::ostringstream message;
    message << "ConstantLyapunovSolver: the Lyapunov operator of Ac is singular to working "
               "precision (1-norm condition number "
            << condition_number_ << " > 1e14; max Re λ(Ac) = " << max_real_eigenvalue_ << ")";
    throw Error(message.str());
  }
  q_packed_.resize(m);
  x_packed_.resize(m);
}

void ConstantLyapunovSolver::solve(const Eigen::Ref<const Eigen::MatrixXd>& Q,
                                   Eigen::Ref<Eigen::MatrixXd> X) const {
  if (Q.rows() != n_ || Q.cols() != n_ || X.rows() != n_ || X.cols() != n_)
    throw Error("ConstantLyapunovSolver::solve: Q and X must be " + std::to_string(n_) + "x" +
                std::to_string(n_) + ", got Q " + shape(Q) + " and X " +
                std::to_string(X.rows()) + "x" + std::to_string(X.cols()));
#ifndef NDEBUG
  // Only the upper triangle is read: an asymmetric Q would be solved silently wrong.
  const double tolerance = 1e-12 * Q.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 0; j < n_; ++j)
    for (Eigen::Index i = 0; i < j; ++i) assert(std::abs(Q(i, j) - Q(j, i)) <= tolerance);
#endif
  Eigen::Index k = 0;
  for (Eigen::Index j = 0; j < n_; ++j)
    for (Eigen::Index i = 0; i <= j; ++i) q_packed_(k++) = Q(i, j);
  x_packed_.noalias() = inverse_ * q_packed_;
  k = 0;
  for (Eigen::Index j = 0; j < n_; ++j)
    for (Eigen::Index i = 0; i <= j; ++i) {
      X(i, j) = x_packed_(k);
      X(j, i) = x_packed_(k++);
    }
}

Eigen::MatrixXd ConstantLyapunovSolver::solve(const Eigen::Ref<const Eigen::MatrixXd>& Q) const {
  Eigen::MatrixXd X(n_, n_);
  solve(Q, X);
  return X;
}

}  // namespace thetad
