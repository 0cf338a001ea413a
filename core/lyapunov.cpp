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

namespace thetad {
namespace {

std::string shape(const Eigen::Ref<const Eigen::MatrixXd>& M) {
  return std::to_string(M.rows()) + "x" + std::to_string(M.cols());
}

// The upper triangle of a square M from its lower one.
void mirror_lower(Eigen::Ref<Eigen::MatrixXd> M) {
  for (Eigen::Index j = 0; j < M.cols(); ++j)
    for (Eigen::Index i = 0; i < j; ++i) M(i, j) = M(j, i);
}

// One block of the sweep below with a 2×2 diagonal block on either side: T_kk'Z + Z T_ll = r,
// vec(Z) in column order, (I ⊗ T_kk' + T_ll' ⊗ I) vec(Z) = vec(r), by a fixed-size LU (the sums
// λi + λj of its eigenvalues are bounded away from 0 by the check in solve()).
template <int bi, int bj, class Reduced>
void solve_block(const Eigen::MatrixXd& T, Eigen::MatrixXd& Y, Eigen::Index i0, Eigen::Index j0, bool symmetric,
                 const Reduced& reduced) {
  constexpr int size = bi * bj;
  Eigen::Matrix<double, size, size> M = Eigen::Matrix<double, size, size>::Zero();
  Eigen::Matrix<double, size, 1> r;
  for (int b = 0; b < bj; ++b)
    for (int a = 0; a < bi; ++a) {
      const int row = a + bi * b;
      r(row) = reduced(i0 + a, j0 + b, i0, j0);
      for (int c = 0; c < bi; ++c) M(row, c + bi * b) += T(i0 + c, i0 + a);
      for (int d = 0; d < bj; ++d) M(row, a + bi * d) += T(j0 + d, j0 + b);
    }
  const Eigen::Matrix<double, size, 1> z = M.partialPivLu().solve(r);
  for (int b = 0; b < bj; ++b)
    for (int a = 0; a < bi; ++a) {
      Y(i0 + a, j0 + b) = z(a + bi * b);
      if (symmetric) Y(j0 + b, i0 + a) = z(a + bi * b);
    }
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

// Eigen's own Householder block size: below it RealSchur is allocation-free as it is, and its
// results stay bit for bit those of before; from it on the in-place product of the reflectors
// (HouseholderSequence::evalTo into its own vectors) avoids the blocked one's allocations.
// RealSchur also divides A by its largest entry before the QR iteration; the Hessenberg form
// there is of A itself, as LAPACK's dgees does without balancing. Below it the buffers of that
// path stay empty.
constexpr Eigen::Index kBlockedFrom = 48;

LyapunovWorkspace::LyapunovWorkspace(Eigen::Index n)
    : n_(n), schur_(std::max<Eigen::Index>(n, 1)), hessenberg_(n < kBlockedFrom ? 0 : n),
      hessenberg_q_(n < kBlockedFrom ? 0 : n, n < kBlockedFrom ? 0 : n),
      householder_workspace_(n < kBlockedFrom ? 0 : n), Y_(n, n), scratch_(n, n), wr_(n), wi_(n) {
  if (n < 1) throw Error("LyapunovWorkspace: n must be at least 1, got " + std::to_string(n));
}

void LyapunovWorkspace::factor(const Eigen::Ref<const Eigen::MatrixXd>& A) {
  factored_ = false;
  if (A.rows() != n_ || A.cols() != n_)
    throw Error("solve_lyapunov: A must be " + std::to_string(n_) + "x" + std::to_string(n_) + ", got " + shape(A));
  if (!A.allFinite()) throw Error("solve_lyapunov: A has non-finite entries");
  a_norm_ = A.norm();
  if (n_ < kBlockedFrom) {
    schur_.compute(A, true);
  } else {
    hessenberg_.compute(A);
    hessenberg_q_ = hessenberg_.packedMatrix();
    Eigen::HouseholderSequence<Eigen::MatrixXd, Eigen::VectorXd>(hessenberg_q_, hessenberg_.householderCoefficients())
        .setLength(n_ - 1)
        .setShift(1)
        .evalTo(hessenberg_q_, householder_workspace_);
    schur_.computeFromHessenberg(hessenberg_.matrixH(), hessenberg_q_, true);
  }
  if (schur_.info() != Eigen::Success) throw Error("solve_lyapunov: the real Schur form of A did not converge");
  // The eigenvalues of the diagonal blocks; RealSchur leaves 2×2 blocks for complex pairs only.
  const Eigen::MatrixXd& T = schur_.matrixT();
  for (Eigen::Index i = 0; i < n_;) {
    if (i + 1 < n_ && T(i + 1, i) != 0.0) {
      const double p = 0.5 * (T(i, i) - T(i + 1, i + 1));
      const double scale = std::max({std::abs(p), std::abs(T(i, i + 1)), std::abs(T(i + 1, i))});
      const double q = p / scale, b = T(i, i + 1) / scale, c = T(i + 1, i) / scale;
      const double z = scale * std::sqrt(std::abs(q * q + b * c));
      wr_(i) = wr_(i + 1) = T(i + 1, i + 1) + p;
      wi_(i) = z;
      wi_(i + 1) = -z;
      i += 2;
    } else {
      wr_(i) = T(i, i);
      wi_(i) = 0.0;
      ++i;
    }
  }
  factored_ = true;
}

// Block forward substitution on T'Y + YT = C, T upper quasi-triangular: the (k, l) block of the
// equation is T_kk'Y_kl + Y_kl T_ll = C_kl − Σ_{i<k} T_ik'Y_il − Σ_{j<l} Y_kj T_jl, where every Y
// on the right is known when the blocks are visited column by column, top to bottom. A symmetric
// C has a symmetric Y: then only the blocks k ≥ l are solved and mirrored, and the row sums read
// columns instead (Y_kj = Y_jk'), which keeps every inner product contiguous.
void LyapunovWorkspace::sweep(bool symmetric) {
  const Eigen::MatrixXd& T = schur_.matrixT();
  const auto block_size = [&](Eigen::Index i) { return i + 1 < n_ && T(i + 1, i) != 0.0 ? 2 : 1; };
  // The right side of entry (i, j) with the known terms subtracted.
  const auto reduced = [&](Eigen::Index i, Eigen::Index j, Eigen::Index i0, Eigen::Index j0) {
    const double row_terms = symmetric ? Y_.col(i).head(j0).dot(T.col(j).head(j0))
                                       : Y_.row(i).head(j0).dot(T.col(j).head(j0));
    return Y_(i, j) - T.col(i).head(i0).dot(Y_.col(j).head(i0)) - row_terms;
  };
  for (Eigen::Index j0 = 0; j0 < n_;) {
    const Eigen::Index bj = block_size(j0);
    for (Eigen::Index i0 = symmetric ? j0 : 0; i0 < n_;) {
      const Eigen::Index bi = block_size(i0);
      if (bi == 1 && bj == 1) {
        Y_(i0, j0) = reduced(i0, j0, i0, j0) / (T(i0, i0) + T(j0, j0));
        if (symmetric) Y_(j0, i0) = Y_(i0, j0);
      } else if (bi == 2 && bj == 2) {
        solve_block<2, 2>(T, Y_, i0, j0, symmetric, reduced);
      } else if (bi == 2) {
        solve_block<2, 1>(T, Y_, i0, j0, symmetric, reduced);
      } else {
        solve_block<1, 2>(T, Y_, i0, j0, symmetric, reduced);
      }
      i0 += bi;
    }
    j0 += bj;
  }
}

void LyapunovWorkspace::solve(const Eigen::Ref<const Eigen::MatrixXd>& Q, Eigen::Ref<Eigen::MatrixXd> X,
                              bool refuse_singular) {
  if (!factored_) throw Error("LyapunovWorkspace::solve: factor(A) first");
  if (Q.rows() != n_ || Q.cols() != n_ || X.rows() != n_ || X.cols() != n_)
    throw Error("solve_lyapunov: Q and X must be " + std::to_string(n_) + "x" + std::to_string(n_) + ", got Q " +
                shape(Q) + " and X " + std::to_string(X.rows()) + "x" + std::to_string(X.cols()));

  // The operator's eigenvalues are λi + λj; checking them here gives a message that names the
  // cause instead of a silently huge solution. Squared moduli: no hypot in the O(n²) loop.
  double smallest_squared = std::numeric_limits<double>::infinity();
  for (Eigen::Index j = 0; j < n_; ++j)
    for (Eigen::Index i = j; i < n_; ++i) {
      const double re = wr_(i) + wr_(j);
      const double im = wi_(i) + wi_(j);
      smallest_squared = std::min(smallest_squared, re * re + im * im);
    }
  const double smallest = std::sqrt(smallest_squared);
  const double threshold = 1e-10 * std::max(a_norm_, 1.0);
  if (refuse_singular && smallest <= threshold) {
    std::ostringstream message;
    message << "solve_lyapunov: the Lyapunov operator X -> A'X + XA is singular to working "
               "precision: min |λi(A) + λj(A)| = "
            << smallest << " <= " << threshold
            << " (A and -A share an eigenvalue, e.g. an eigenvalue on the imaginary axis)";
    throw Error(message.str());
  }

  // A = U T U' turns A'X + XA = −Q into T'Y + YT = −U'QU, Y = U'XU.
  const Eigen::MatrixXd& U = schur_.matrixU();
  const bool symmetric = Q == Q.transpose();
  // Symmetric: both triple products are formed on their lower half only, and mirrored.
  scratch_.noalias() = U.transpose() * Q;
  if (symmetric) {
    Y_.triangularView<Eigen::Lower>() = -scratch_ * U;
    mirror_lower(Y_);
  } else {
    Y_.noalias() = -scratch_ * U;
  }
  sweep(symmetric);
  scratch_.noalias() = U * Y_;
  if (symmetric) {
    X.triangularView<Eigen::Lower>() = scratch_ * U.transpose();
    mirror_lower(X);
  } else {
    X.noalias() = scratch_ * U.transpose();
  }
  if (!X.allFinite()) throw Error("solve_lyapunov: the solution is not finite (the equation is too ill-conditioned)");
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
