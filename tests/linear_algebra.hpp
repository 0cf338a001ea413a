#pragma once

// Eigen's decompositions as the tests use them to check a result (a spectrum, a rank), compiled
// once in tests/linear_algebra.cpp (library thetad_test_support). Written out in a test, each is
// instantiated and optimized again in that test's unit: EigenSolver ~9 s of compile, JacobiSVD
// ~7 s on double and as much on complex (docs/performance-log.md, 2026-12-02).

#include <Eigen/Core>

namespace thetad::testing {

// The eigenvalues of A: Eigen::EigenSolver(A, false).eigenvalues().
Eigen::VectorXcd eigenvalues_of(const Eigen::Ref<const Eigen::MatrixXd>& A);

// The largest real part of an eigenvalue of A.
double max_real_eigenvalue(const Eigen::Ref<const Eigen::MatrixXd>& A);

// The operator 2-norm of A (its largest singular value): Eigen's operatorNorm(), which runs a
// self-adjoint eigensolver.
double operator_norm_of(const Eigen::Ref<const Eigen::MatrixXd>& A);

// The singular values of A, largest first: Eigen::JacobiSVD(A).singularValues().
Eigen::VectorXd singular_values_of(const Eigen::Ref<const Eigen::MatrixXd>& A);
Eigen::VectorXd singular_values_of(const Eigen::Ref<const Eigen::MatrixXcd>& A);

}  // namespace thetad::testing
