#include "core/stabilizability_margin.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include "core/care_weights.hpp"
#include "core/error.hpp"
#include "core/lapack.hpp"

namespace thetad {

using care::shape;

StabilizabilityMargin::StabilizabilityMargin(Eigen::Index n, const Eigen::Ref<const Eigen::MatrixXd>& R)
    : n_(n), m_(R.rows()) {
  if (n_ < 1 || m_ < 1 || R.cols() != m_)
    throw Error("stabilizability margin: needs n >= 1 and a square, non-empty R, got n = " + std::to_string(n_) +
                " and R " + shape(R));
  const Eigen::LLT<Eigen::MatrixXd> llt(R);
  if (!R.allFinite() || llt.info() != Eigen::Success || !R.isApprox(R.transpose()))
    throw Error("stabilizability margin: R must be symmetric positive definite");
  weight_ = llt.matrixU().solve(Eigen::MatrixXd::Identity(m_, m_));
  A_.resize(n_, n_);
  scaled_input_.resize(n_, m_);
  real_.resize(n_);
  imaginary_.resize(n_);
  pencil_.resize(n_, n_ + m_);
  singular_values_.resize(n_);
  svd_real_work_.resize(5 * n_);

  // The workspace queries of both LAPACK routines.
  const auto order = static_cast<lapack_int>(n_), columns = static_cast<lapack_int>(n_ + m_);
  double eigen_size = 0.0, unused = 0.0;
  if (LAPACKE_dgeev_work(LAPACK_COL_MAJOR, 'N', 'N', order, A_.data(), order, real_.data(), imaginary_.data(), &unused,
                         1, &unused, 1, &eigen_size, -1) != 0)
    throw Error("stabilizability margin: the dgeev workspace query failed");
  eigen_work_.resize(std::max<Eigen::Index>(static_cast<Eigen::Index>(eigen_size), 3 * n_));
  std::complex<double> svd_size = 0.0, none = 0.0;
  if (LAPACKE_zgesvd_work(LAPACK_COL_MAJOR, 'N', 'N', order, columns, pencil_.data(), order, singular_values_.data(),
                          &none, 1, &none, 1, &svd_size, -1, svd_real_work_.data()) != 0)
    throw Error("stabilizability margin: the zgesvd workspace query failed");
  svd_work_.resize(std::max<Eigen::Index>(static_cast<Eigen::Index>(svd_size.real()), 3 * n_ + m_));
}

double StabilizabilityMargin::evaluate(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                       const Eigen::Ref<const Eigen::MatrixXd>& B) {
  if (A.rows() != n_ || A.cols() != n_ || B.rows() != n_ || B.cols() != m_)
    throw Error("stabilizability margin: A is " + shape(A) + " and B " + shape(B) + ", sized for n = " +
                std::to_string(n_) + ", m = " + std::to_string(m_));
  const auto order = static_cast<lapack_int>(n_), columns = static_cast<lapack_int>(n_ + m_);
  A_ = A;
  double unused = 0.0;
  if (LAPACKE_dgeev_work(LAPACK_COL_MAJOR, 'N', 'N', order, A_.data(), order, real_.data(), imaginary_.data(), &unused,
                         1, &unused, 1, eigen_work_.data(), static_cast<lapack_int>(eigen_work_.size())) != 0)
    throw Error("stabilizability margin: the eigenvalues of A were not found (dgeev)");
  scaled_input_.noalias() = B * weight_;
  const double counted_from = -10.0 * std::sqrt(std::numeric_limits<double>::epsilon()) * A.norm();
  double margin = std::numeric_limits<double>::infinity();
  for (Eigen::Index k = 0; k < n_; ++k) {
    // A real A's conjugate eigenvalues give conjugate matrices, which have the same singular values.
    if (real_[k] < counted_from || imaginary_[k] < 0.0) continue;
    pencil_.leftCols(n_) = A.cast<std::complex<double>>();
    pencil_.leftCols(n_).diagonal().array() -= std::complex<double>(real_[k], imaginary_[k]);
    pencil_.rightCols(m_) = scaled_input_.cast<std::complex<double>>();
    std::complex<double> none = 0.0;
    if (LAPACKE_zgesvd_work(LAPACK_COL_MAJOR, 'N', 'N', order, columns, pencil_.data(), order, singular_values_.data(),
                            &none, 1, &none, 1, svd_work_.data(), static_cast<lapack_int>(svd_work_.size()),
                            svd_real_work_.data()) != 0)
      throw Error("stabilizability margin: the singular values of [A - λI, B R^(-1/2)] were not found (zgesvd)");
    margin = std::min(margin, singular_values_[n_ - 1]);  // descending
  }
  return margin;
}

double stabilizability_margin(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                              const Eigen::Ref<const Eigen::MatrixXd>& R) {
  return StabilizabilityMargin(A.rows(), R).evaluate(A, B);
}

}  // namespace thetad
