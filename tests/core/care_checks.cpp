#include "tests/core/care_checks.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "tests/linear_algebra.hpp"

namespace thetad::testing {

void expect_valid_care(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                       const Eigen::Ref<const Eigen::MatrixXd>& Q, const Eigen::Ref<const Eigen::MatrixXd>& R,
                       const CareResult& result, double tol) {
  const Eigen::Index n = A.rows();
  const Eigen::Index m = B.cols();
  ASSERT_EQ(result.P.rows(), n);
  ASSERT_EQ(result.P.cols(), n);
  ASSERT_EQ(result.K.rows(), m);
  ASSERT_EQ(result.K.cols(), n);
  ASSERT_EQ(result.closed_loop_eigenvalues.size(), n);
  ASSERT_TRUE(result.P.allFinite());
  ASSERT_TRUE(result.K.allFinite());
  EXPECT_GE(result.iterations, 0);

  const Eigen::MatrixXd& P = result.P;
  EXPECT_EQ((P - P.transpose()).norm(), 0.0) << "P is not symmetric";
  const Eigen::VectorXd p_eigenvalues = P.selfadjointView<Eigen::Lower>().eigenvalues();
  const double p_norm = std::max(std::abs(p_eigenvalues(0)), std::abs(p_eigenvalues(n - 1)));
  EXPECT_GE(p_eigenvalues(0), -tol * p_norm) << "P is not positive semi-definite";

  const Eigen::MatrixXd G = B * R.llt().solve(B.transpose());
  const Eigen::MatrixXd residual = A.transpose() * P + P * A - P * G * P + Q;
  const double terms = Q.norm() + 2.0 * A.norm() * P.norm() + G.norm() * P.norm() * P.norm();
  EXPECT_LE(residual.norm(), tol * std::max(terms, std::numeric_limits<double>::min()))
      << "CARE normwise residual too large (size of the terms " << terms << ")";
  const double q_scale = std::max(1.0, Q.norm());
  EXPECT_NEAR(result.relative_residual, residual.norm() / q_scale, 1e-13 * terms / q_scale);

  const Eigen::MatrixXd BtP = B.transpose() * P;
  EXPECT_LE((R * result.K - BtP).norm(), tol * R.norm() * result.K.norm()) << "K is not R⁻¹B'P";

  for (Eigen::Index i = 0; i < n; ++i)
    EXPECT_LT(result.closed_loop_eigenvalues(i).real(), 0.0) << "reported closed-loop eigenvalue " << i;
  const Eigen::VectorXcd recomputed = eigenvalues_of(A - B * result.K);
  for (Eigen::Index i = 0; i < n; ++i) EXPECT_LT(recomputed(i).real(), 0.0) << "closed-loop eigenvalue " << i;
}

}  // namespace thetad::testing
