#pragma once

// The one check every CARE test runs on a solution (after Drake's riccati test helper).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <limits>

#include "core/riccati.hpp"

namespace thetad::testing {

// Expects `result` to be the stabilizing solution of A'P + PA − PBR⁻¹B'P + Q = 0:
//  - P exactly symmetric and positive semi-definite (min eig ≥ −tol·‖P‖₂);
//  - residual: ‖Res‖_F ≤ tol · max(1, ‖Q‖_F, ‖A'P + PA‖_F, ‖PGP‖_F). When the terms are no
//    larger than Q this is the relative residual of CareResult ≤ tol. On ill-conditioned
//    equations the terms are much larger than Q and cancel; rounding in forming them (by any
//    backward-stable solver, and by this check itself) is then relative to their size, so the
//    bound scales with the largest term. result.relative_residual must agree with the
//    recomputed one;
//  - K = R⁻¹B'P (‖RK − B'P‖_F ≤ tol·max(1, ‖B'P‖_F));
//  - every reported and every recomputed eigenvalue of A − BK has Re λ < 0.
inline void expect_valid_care(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                              const Eigen::Ref<const Eigen::MatrixXd>& Q, const Eigen::Ref<const Eigen::MatrixXd>& R,
                              const CareResult& result, double tol = 1e-10) {
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
  const Eigen::MatrixXd linear = A.transpose() * P + P * A;
  const Eigen::MatrixXd quadratic = P * G * P;
  const Eigen::MatrixXd residual = linear - quadratic + Q;
  const double scale = std::max({1.0, Q.norm(), linear.norm(), quadratic.norm()});
  EXPECT_LE(residual.norm(), tol * scale) << "CARE residual too large (scale " << scale << ")";
  const double relative = residual.norm() / std::max(1.0, Q.norm());
  // Both are rounding-level quantities when tiny, so compare them to the scale, not each other.
  EXPECT_NEAR(result.relative_residual, relative, 1e-3 * relative + 1e-14 * scale / std::max(1.0, Q.norm()));

  const Eigen::MatrixXd BtP = B.transpose() * P;
  EXPECT_LE((R * result.K - BtP).norm(), tol * std::max(1.0, BtP.norm())) << "K is not R⁻¹B'P";

  for (Eigen::Index i = 0; i < n; ++i)
    EXPECT_LT(result.closed_loop_eigenvalues(i).real(), 0.0) << "reported closed-loop eigenvalue " << i;
  const Eigen::VectorXcd recomputed = Eigen::EigenSolver<Eigen::MatrixXd>(A - B * result.K, false).eigenvalues();
  for (Eigen::Index i = 0; i < n; ++i) EXPECT_LT(recomputed(i).real(), 0.0) << "closed-loop eigenvalue " << i;
}

}  // namespace thetad::testing
