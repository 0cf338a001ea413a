// Capped Newton–Kleinman: exactly the requested number of Kleinman steps (checked against the
// textbook form of the step, solved independently), ρ of the P it returns, and refusals that say
// which step failed.
#include "core/capped_newton_kleinman.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bench/care_problems.hpp"
#include "core/error.hpp"
#include "core/lyapunov.hpp"
#include "core/riccati.hpp"
#include "tests/error_message.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using ::testing::HasSubstr;

// Kleinman's step as he wrote it: P_{k+1} solves (A − G P_k)'P + P(A − G P_k) + Q + P_k G P_k = 0.
MatrixXd kleinman_steps(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R, MatrixXd P,
                        int steps) {
  const MatrixXd G = B * R.llt().solve(B.transpose());
  for (int k = 0; k < steps; ++k) P = solve_lyapunov(A - G * P, Q + P * G * P);
  return P;
}

// A random problem with the paper's spread of weights (bench/care_problems.hpp) and a
// stabilizing P0 off its solution.
struct Problem {
  bench::CareProblem care;
  MatrixXd P0;
};

Problem near_solution(double perturbation) {
  std::mt19937_64 rng(7);
  Problem p{bench::random_care_problem("n8", 8, 3, rng), {}};
  const MatrixXd P = solve_care(p.care.A, p.care.B, p.care.Q, p.care.R).P;
  p.P0 = (1.0 + perturbation) * P;  // a larger gain on every input: stabilizing (LQR gain margin)
  return p;
}

TEST(CappedNewtonKleinman, TakesExactlyTheRequestedKleinmanSteps) {
  const Problem p = near_solution(1e-3);
  for (const int steps : {1, 2, 3}) {
    CappedNewtonKleinman solver(p.care.Q, p.care.R, steps);
    const MatrixXd& P = solver.solve(p.care.A, p.care.B, p.P0);
    const MatrixXd expected = kleinman_steps(p.care.A, p.care.B, p.care.Q, p.care.R, p.P0, steps);
    EXPECT_LE((P - expected).norm(), 1e-9 * expected.norm()) << steps << " steps";
    EXPECT_EQ(P, P.transpose());
  }
}

TEST(CappedNewtonKleinman, ReportsTheResidualOfItsPAndConvergesQuadratically) {
  const Problem p = near_solution(1e-3);
  std::vector<double> rho;
  for (const int steps : {1, 2, 3, 6}) {
    CappedNewtonKleinman solver(p.care.Q, p.care.R, steps);
    solver.solve(p.care.A, p.care.B, p.P0);
    rho.push_back(solver.last_residual_to_terms());
  }
  EXPECT_LT(rho[1], 1e-2 * rho[0]);
  EXPECT_LT(rho[3], 1e-13);
  const MatrixXd P = solve_care(p.care.A, p.care.B, p.care.Q, p.care.R).P;
  CappedNewtonKleinman solver(p.care.Q, p.care.R, 6);
  EXPECT_LE((solver.solve(p.care.A, p.care.B, p.P0) - P).norm(), 1e-10 * P.norm());
}

TEST(CappedNewtonKleinman, RefusesAStartWhoseClosedLoopIsNotHurwitzNamingTheStep) {
  // ẋ = x + u from P0 = 0: A − G P0 = 1.
  const MatrixXd one = MatrixXd::Ones(1, 1);
  CappedNewtonKleinman solver(one, one, 2);
  EXPECT_THAT(testing::error_message([&] { solver.solve(one, one, MatrixXd::Zero(1, 1)); }),
              HasSubstr("not Hurwitz before step 1 (largest Re λ 1)"));
  // P0 = 3 stabilizes (1 − 3 < 0): the iteration then heads to P = 1 + √2.
  EXPECT_NEAR(CappedNewtonKleinman(one, one, 8).solve(one, one, 3.0 * one)(0, 0), 1.0 + std::sqrt(2.0), 1e-14);
}

TEST(CappedNewtonKleinman, RefusesNoStepsAndSizesThatDoNotFit) {
  const MatrixXd one = MatrixXd::Ones(1, 1);
  EXPECT_THAT(testing::error_message([&] { CappedNewtonKleinman(one, one, 0); }), HasSubstr("at least one step"));
  CappedNewtonKleinman solver(one, one, 1);
  EXPECT_THROW(solver.solve(one, one, MatrixXd::Ones(2, 2)), Error);
}

}  // namespace
}  // namespace thetad
