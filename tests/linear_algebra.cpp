#include "tests/linear_algebra.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace thetad::testing {

Eigen::VectorXcd eigenvalues_of(const Eigen::Ref<const Eigen::MatrixXd>& A) {
  return Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
}

double max_real_eigenvalue(const Eigen::Ref<const Eigen::MatrixXd>& A) { return eigenvalues_of(A).real().maxCoeff(); }

double operator_norm_of(const Eigen::Ref<const Eigen::MatrixXd>& A) { return Eigen::MatrixXd(A).operatorNorm(); }

Eigen::VectorXd singular_values_of(const Eigen::Ref<const Eigen::MatrixXd>& A) {
  return Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
}

Eigen::VectorXd singular_values_of(const Eigen::Ref<const Eigen::MatrixXcd>& A) {
  return Eigen::JacobiSVD<Eigen::MatrixXcd>(A).singularValues();
}

}  // namespace thetad::testing
