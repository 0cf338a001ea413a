// CareSolver, the workspace form of solve_care that the SDRE's cold step uses: the same answer as
// solve_care bit for bit, nothing carried over from one solve to the next, and no heap allocation
// in solve() (counted, as in tests/controllers/control_step_allocation_test.cpp).
#include "core/riccati.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "tests/core/care_checks.hpp"
#include "tests/error_message.hpp"
#include "tests/heap_counter.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;

struct Equation {
  MatrixXd A, B, Q, R;
};

// A stabilizable equation with unstable modes and weights over seven decades, as the paper's.
Equation random_equation(Eigen::Index n, Eigen::Index m, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> exponent(0.0, 7.0);
  const auto random = [&](Eigen::Index rows, Eigen::Index cols) {
    return MatrixXd(MatrixXd::NullaryExpr(rows, cols, [&]() { return normal(rng); }));
  };
  Equation e{random(n, n) / std::sqrt(static_cast<double>(n)), random(n, m), MatrixXd::Zero(n, n),
             MatrixXd::Zero(m, m)};
  for (Eigen::Index i = 0; i < n; ++i) e.Q(i, i) = std::pow(10.0, exponent(rng));
  for (Eigen::Index i = 0; i < m; ++i) e.R(i, i) = std::pow(10.0, exponent(rng));
  return e;
}

void expect_identical(const CareResult& a, const CareResult& b) {
  EXPECT_EQ(a.P, b.P);
  EXPECT_EQ(a.K, b.K);
  EXPECT_EQ(a.closed_loop_eigenvalues, b.closed_loop_eigenvalues);
  EXPECT_EQ(a.relative_residual, b.relative_residual);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.sign_iterations, b.sign_iterations);
}

// Sizes on both sides of Eigen's blocking thresholds (48 for Householder products).
TEST(CareSolver, SameAnswerAsSolveCareOverSeveralSolvesWithoutAllocating) {
  const long probe = testing::heap_allocations_during([] { std::vector<double> v(4); });
  for (const auto& [n, m] : {std::pair<Eigen::Index, Eigen::Index>{6, 2}, {18, 5}, {60, 20}}) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(100 * n + m));
    const Equation first = random_equation(n, m, rng);
    Equation second = random_equation(n, m, rng);
    second.Q = first.Q;
    second.R = first.R;
    for (const auto& [method, method_name] : testing::kCareMethods) {
      SCOPED_TRACE("n=" + std::to_string(n) + " " + method_name);
      CareSolver solver(first.Q, first.R, method);
      for (const Equation* e : std::initializer_list<const Equation*>{&first, &second, &first}) {
        const CareResult expected = solve_care(e->A, e->B, e->Q, e->R, method);
        testing::expect_valid_care(e->A, e->B, e->Q, e->R, expected, 1e-9);
        const CareResult* result = nullptr;
        const long allocations = testing::heap_allocations_during([&] { result = &solver.solve(e->A, e->B); });
        expect_identical(*result, expected);
        if (probe >= 0) {
          EXPECT_EQ(allocations, 0);
        }
      }
    }
  }
}

// StabilityProof::lyapunov (the SDRE's): the same P, K and residual bit for bit, with no
// eigensolver where the certificate holds (then the eigenvalues are NaN), the spectrum otherwise;
// the Schur method's spectrum comes free and is always reported.
TEST(CareSolver, TheLyapunovCertificateReplacesOnlyTheEigensolver) {
  const long probe = testing::heap_allocations_during([] { std::vector<double> v(4); });
  int certified = 0;
  for (const auto& [n, m] : {std::pair<Eigen::Index, Eigen::Index>{6, 2}, {18, 5}, {60, 20}}) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(100 * n + m));
    const Equation e = random_equation(n, m, rng);
    for (const auto& [method, method_name] : testing::kCareMethods) {
      SCOPED_TRACE("n=" + std::to_string(n) + " " + method_name);
      const CareResult expected = solve_care(e.A, e.B, e.Q, e.R, method);
      CareSolver solver(e.Q, e.R, method, StabilityProof::lyapunov);
      const CareResult* result = nullptr;
      const long allocations = testing::heap_allocations_during([&] { result = &solver.solve(e.A, e.B); });
      EXPECT_EQ(result->P, expected.P);
      EXPECT_EQ(result->K, expected.K);
      EXPECT_EQ(result->relative_residual, expected.relative_residual);
      EXPECT_EQ(result->sign_iterations, expected.sign_iterations);
      if (result->closed_loop_eigenvalues.array().isNaN().all()) {
        EXPECT_GT(expected.sign_iterations, 0) << "certified on the Schur path, whose spectrum is free";
        ++certified;
      } else {
        EXPECT_EQ(result->closed_loop_eigenvalues, expected.closed_loop_eigenvalues);
      }
      if (probe >= 0) {
        EXPECT_EQ(allocations, 0);
      }
    }
  }
  // automatic and matrix_sign at each size take the sign path here, and Q ≻ 0.
  EXPECT_EQ(certified, 6);
}

TEST(CareSolver, RefusesWhatSolveCareRefuses) {
  // The unstabilizable pair of care_errors_test: the same message from both.
  const MatrixXd A = Eigen::Vector2d(1, 2).asDiagonal();
  const MatrixXd B = Eigen::Vector2d(1, 0);
  const MatrixXd Q = MatrixXd::Identity(2, 2);
  const MatrixXd R = testing::scalar(1);
  for (const auto& entry : testing::kCareMethods) {
    // Not a structured binding: Clang 14 cannot capture one in a lambda.
    const auto method = entry.first;
    SCOPED_TRACE(entry.second);
    const std::string expected = testing::error_message([&] { solve_care(A, B, Q, R, method); });
    CareSolver solver(Q, R, method);
    EXPECT_THAT(expected, ::testing::HasSubstr("not stabilizable"));
    EXPECT_EQ(testing::error_message([&] { solver.solve(A, B); }), expected);
  }
}

}  // namespace
}  // namespace thetad
