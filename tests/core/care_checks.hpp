#pragma once

// The one check every CARE test runs on a solution (after Drake's riccati test helper).
// Compiled once, in care_checks.cpp (library thetad_test_support): defined inline here, its
// EigenSolver, self-adjoint eigensolver and LLT were instantiated and optimized again in each of
// the eight tests that include it, ~9 s of compile each (docs/performance-log.md, 2026-12-02).

#include <utility>

#include <Eigen/Dense>

#include "core/riccati.hpp"

namespace thetad::testing {

// A 1×1 matrix: scalar equations in the CARE tests.
inline Eigen::MatrixXd scalar(double v) { return Eigen::MatrixXd::Constant(1, 1, v); }

// Every method of solve_care, with its name for messages.
inline constexpr std::pair<CareMethod, const char*> kCareMethods[] = {
    {CareMethod::automatic, "automatic"}, {CareMethod::matrix_sign, "matrix_sign"}, {CareMethod::schur, "schur"}};

// Expects `result` to be the stabilizing solution of A'P + PA − PBR⁻¹B'P + Q = 0:
//  - P exactly symmetric and positive semi-definite (min eig ≥ −tol·‖P‖₂);
//  - residual: the normwise residual ‖Res‖_F / (‖Q‖_F + 2‖A‖_F‖P‖_F + ‖G‖_F‖P‖_F²) ≤ tol. When P
//    is no larger than Q this is about CareResult::relative_residual. On ill-conditioned
//    equations the terms of the sum are much larger than Q and cancel; a backward-stable solver
//    (and this check itself) then makes rounding errors relative to the terms, not to Q, so the
//    bound is on the normwise (backward-error) residual. result.relative_residual must agree
//    with the recomputed one to within that rounding;
//  - K = R⁻¹B'P (‖RK − B'P‖_F ≤ tol·‖R‖_F‖K‖_F: the rounding of forming either side);
//  - every reported and every recomputed eigenvalue of A − BK has Re λ < 0.
void expect_valid_care(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                       const Eigen::Ref<const Eigen::MatrixXd>& Q, const Eigen::Ref<const Eigen::MatrixXd>& R,
                       const CareResult& result, double tol = 1e-10);

}  // namespace thetad::testing
