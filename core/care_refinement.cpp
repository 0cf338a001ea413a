#include "core/care_refinement.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/lapack.hpp"

// Built with -ffp-contract=off (core/CMakeLists.txt): a fused multiply-add in place of a product
// and a subtraction would break the error-free transformations below.

namespace thetad {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;

// a = hi + lo exactly, each with at most 26 significant bits (Veltkamp's split, 2^27 + 1), so that
// the products of halves are exact.
inline void split(double a, double& hi, double& lo) {
  const double c = 134217729.0 * a;
  hi = c - (c - a);
  lo = a - hi;
}

// s + e = a + b exactly (Knuth's two-sum).
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double z = s - a;
  e = (a - (s - z)) + (b - z);
}

// p + e = a·b exactly, from the halves of a and b (Dekker's two-product).
inline void two_product(double a, double a_hi, double a_lo, double b, double b_hi, double b_lo, double& p, double& e) {
  p = a * b;
  e = ((a_hi * b_hi - p) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
}

void split_matrix(const MatrixXd& X, MatrixXd& hi, MatrixXd& lo) {
  for (Index j = 0; j < X.cols(); ++j)
    for (Index i = 0; i < X.rows(); ++i) split(X(i, j), hi(i, j), lo(i, j));
}

// sum + err = (X + X_low)·Y with the rounding errors of X·Y carried in err (Dot2): X comes with its
// halves; X_low, a correction at the rounding level of X, is multiplied in plain arithmetic, its
// products' errors being of order eps² of the terms. Column by column, so that the inner loop runs
// down contiguous columns and vectorizes.
void compensated_product(const MatrixXd& X, const MatrixXd& X_hi, const MatrixXd& X_lo, const MatrixXd* X_low,
                         const care::MatrixRef& Y, MatrixXd& sum, MatrixXd& err) {
  const Index rows = X.rows();
  for (Index j = 0; j < Y.cols(); ++j) {
    double* s = sum.col(j).data();
    double* c = err.col(j).data();
    for (Index i = 0; i < rows; ++i) s[i] = c[i] = 0.0;
    for (Index k = 0; k < X.cols(); ++k) {
      const double y = Y(k, j);
      // An exact zero adds nothing, exactly: the helicopter's A and B are mostly zeros (22 and 6
      // nonzeros in the paper's 18×18 and 18×5), and the SDRE's cold solves run this on each.
      if (y == 0.0) continue;
      double y_hi = 0.0;
      double y_lo = 0.0;
      split(y, y_hi, y_lo);
      const double* x = X.col(k).data();
      const double* x_hi = X_hi.col(k).data();
      const double* x_lo = X_lo.col(k).data();
      for (Index i = 0; i < rows; ++i) {
        double p = 0.0;
        double e = 0.0;
        double t = 0.0;
        two_product(x[i], x_hi[i], x_lo[i], y, y_hi, y_lo, p, e);
        two_sum(s[i], p, s[i], t);
        c[i] += t + e;
      }
      if (X_low != nullptr) {
        const double* x_low = X_low->col(k).data();
        for (Index i = 0; i < rows; ++i) c[i] += x_low[i] * y;
      }
    }
  }
}

}  // namespace

CareRefinement::CareRefinement(Index n, Index m)
    : n_(n), m_(m), lyapunov_(n), P_scaled_(n, n), P_hi_(n, n), P_lo_(n, n), Z_(n, n), Z_err_(n, n), N_(n, m),
      N_err_(n, m), N_hi_(n, m), N_lo_(n, m), K_(m, n), E_(m, n), V_(n, n), V_err_(n, n), KE_(n, n), residual_(n, n),
      Ac_(n, n), scaled_(n, n), identity_(MatrixXd::Identity(n, n)), H_(n, n), balance_(n) {}

void CareRefinement::compute_residual(const care::MatrixRef& A, const care::MatrixRef& B, const care::MatrixRef& R,
                                      const care::Weights& w, const MatrixXd& P) {
  // P, Q and R times a power of two σ ≈ 1/‖P‖ (exact), so that no product over- or underflows
  // whatever the scale of the weights: Res is homogeneous of degree one in (P, Q, R), K of degree
  // zero. Below, every quantity but K is σ times its true value until Res is divided back.
  const double p_norm = care::frobenius_norm(P);
  sigma_ = p_norm > 0.0 && std::isfinite(p_norm) ? std::ldexp(1.0, -std::ilogb(p_norm)) : 1.0;
  const double sigma = sigma_;
  P_scaled_ = sigma * P;
  split_matrix(P_scaled_, P_hi_, P_lo_);
  compensated_product(P_scaled_, P_hi_, P_lo_, nullptr, A, Z_, Z_err_);  // PA = (A'P)'
  compensated_product(P_scaled_, P_hi_, P_lo_, nullptr, B, N_, N_err_);  // PB = M', M = B'P
  K_ = N_.transpose();
  w.L.triangularView<Eigen::Lower>().solveInPlace(K_);
  w.L.transpose().triangularView<Eigen::Upper>().solveInPlace(K_);
  K_ /= sigma;
  split_matrix(N_, N_hi_, N_lo_);
  compensated_product(N_, N_hi_, N_lo_, &N_err_, K_, V_, V_err_);  // M'K
  // E = RK − M cancels to the rounding level of M: compensated, then small enough for K'E in
  // plain arithmetic.
  for (Index j = 0; j < n_; ++j)
    for (Index i = 0; i < m_; ++i) {
      double s = -N_(j, i);
      double c = -N_err_(j, i);
      for (Index k = 0; k < m_; ++k) {
        const double r = sigma * R(i, k);
        double r_hi = 0.0, r_lo = 0.0, k_hi = 0.0, k_lo = 0.0, p = 0.0, e = 0.0, t = 0.0;
        split(r, r_hi, r_lo);
        split(K_(k, j), k_hi, k_lo);
        two_product(r, r_hi, r_lo, K_(k, j), k_hi, k_lo, p, e);
        two_sum(s, p, s, t);
        c += t + e;
      }
      E_(i, j) = s + c;
    }
  KE_.noalias() = K_.transpose() * E_;
  // Res = A'P + PA + Q − M'K + K'E (= … − M'K − K'M + K'RK), symmetric in exact arithmetic; the
  // terms that cancel are summed exactly and their errors added once.
  for (Index j = 0; j < n_; ++j)
    for (Index i = 0; i <= j; ++i) {
      double s = Z_(j, i);
      double c = Z_err_(j, i) + Z_err_(i, j) - V_err_(i, j) + KE_(i, j);
      double t = 0.0;
      two_sum(s, Z_(i, j), s, t);
      c += t;
      two_sum(s, sigma * w.Q(i, j), s, t);
      c += t;
      two_sum(s, -V_(i, j), s, t);
      c += t;
      residual_(i, j) = residual_(j, i) = (s + c) / sigma;
    }
}

bool CareRefinement::balance_closed_loop(const care::MatrixRef& A, const care::MatrixRef& B) {
  Ac_ = A;
  Ac_.noalias() -= B * K_;
  const auto n = static_cast<lapack_int>(n_);
  lapack_int ilo = 0;
  lapack_int ihi = 0;
  return LAPACKE_dgebal_work(LAPACK_COL_MAJOR, 'S', n, Ac_.data(), n, &ilo, &ihi, balance_.data()) == 0;
}

// Both norms of σ times their matrices: the ratio is the same, and the sums of squares stay in range.
double CareRefinement::balanced_residual_ratio(const MatrixXd& P) const {
  double residual = 0.0;
  double solution = 0.0;
  for (Index j = 0; j < n_; ++j)
    for (Index i = 0; i < n_; ++i) {
      const double d = sigma_ * balance_(i) * balance_(j);
      residual += (d * residual_(i, j)) * (d * residual_(i, j));
      solution += (d * P(i, j)) * (d * P(i, j));
    }
  return std::sqrt(residual) / (care::frobenius_norm(Ac_) * std::sqrt(solution));
}

bool CareRefinement::factor_closed_loop() {
  try {
    lyapunov_.factor(Ac_);
  } catch (const Error&) {
    return false;
  }
  return lyapunov_.max_real_eigenvalue() < 0.0;
}

// Ac = D Ãc D⁻¹ turns Ac'Δ + ΔAc + W = 0 into Ãc'(DΔD) + (DΔD)Ãc + DWD = 0.
bool CareRefinement::solve_balanced(const MatrixXd& W, MatrixXd& X, bool even_if_singular) {
  scaled_ = balance_.asDiagonal() * W * balance_.asDiagonal();
  try {
    lyapunov_.solve(scaled_, X, !even_if_singular);
  } catch (const Error&) {
    return false;
  }
  X = balance_.cwiseInverse().asDiagonal() * X * balance_.cwiseInverse().asDiagonal();
  return X.allFinite();
}

bool CareRefinement::correction(MatrixXd& delta, bool even_if_singular) {
  return solve_balanced(residual_, delta, even_if_singular);
}

double CareRefinement::lyapunov_inverse_norm() {
  if (!solve_balanced(identity_, H_, true)) return std::numeric_limits<double>::quiet_NaN();
  return care::frobenius_norm(H_);
}

}  // namespace thetad
