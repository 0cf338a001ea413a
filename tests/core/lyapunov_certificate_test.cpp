// The Lyapunov certificate: whenever it says the closed loop of a CARE iterate is Hurwitz, the
// spectrum agrees (random iterates near the stabilizing solution and far from it, some with
// unstable closed loops); it holds at the stabilizing solution when Q ≻ 0 and on the paper's
// problem; it never holds at a solution of the CARE that does not stabilize.
#include "core/lyapunov_certificate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <Eigen/Dense>

#include "bench/care_problems.hpp"
#include "core/riccati.hpp"
#include "tests/linear_algebra.hpp"

namespace thetad {
namespace {

using bench::CareProblem;
using Eigen::MatrixXd;

bool certified(const CareProblem& p, const MatrixXd& P) {
  care::Weights w = care::prepare_weights(p.Q, p.R);
  care::set_input_matrix(w, p.B);
  const MatrixXd WP = w.W * P;
  MatrixXd Res(P.rows(), P.cols());
  care::care_residual(p.A, w, P, WP, Res);
  LyapunovCertificate certificate(P.rows());
  return certificate.proves_hurwitz(p.A, w, P, WP, Res);
}

double largest_real_part(const CareProblem& p, const MatrixXd& P) {
  const MatrixXd Ac = p.A - p.B * p.R.llt().solve(p.B.transpose() * P);
  return testing::max_real_eigenvalue(Ac);
}

// Iterates P = P* + δS (S symmetric random) around the stabilizing solution P*, δ from 1e-6 to 10
// times ‖P*‖: near P* the closed loop is stable, far from it often not, and P itself indefinite.
TEST(LyapunovCertificate, WhenItHoldsTheClosedLoopIsHurwitz) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-6.0, 1.0);
  int held = 0, unstable = 0, stable_unproved = 0;
  for (int draw = 0; draw < 400; ++draw) {
    const Eigen::Index n = 2 + draw % 7;
    CareProblem p = bench::random_care_problem("random", n, 1 + n / 3, rng);
    // Half with Q ≻ 0 from the random weights, half with a singular Q.
    if (draw % 2 == 1) p.Q(0, 0) = 0.0;
    const MatrixXd star = solve_care(p.A, p.B, p.Q, p.R).P;
    MatrixXd S = bench::random_normal(n, n, rng);
    S = 0.5 * (S + S.transpose()).eval();
    const MatrixXd P = star + std::pow(10.0, exponent(rng)) * star.norm() / S.norm() * S;
    const double max_real = largest_real_part(p, P);
    if (certified(p, P)) {
      ++held;
      EXPECT_LT(max_real, 0.0) << "draw " << draw << ": certified, but Re λ = " << max_real;
    } else if (max_real < 0.0) {
      ++stable_unproved;
    }
    if (!(max_real < 0.0)) ++unstable;
  }
  // The draws cover both outcomes, so that the implication above is tested, not vacuous.
  EXPECT_GT(held, 100);
  EXPECT_GT(unstable, 50);
  RecordProperty("certified", held);
  RecordProperty("unstable", unstable);
  RecordProperty("stable_but_not_certified", stable_unproved);
}

TEST(LyapunovCertificate, HoldsAtTheStabilizingSolution) {
  std::mt19937_64 rng(11);
  for (const Eigen::Index n : {3, 6, 18, 40}) {
    const CareProblem p = bench::random_care_problem("random_n" + std::to_string(n), n, 1 + n / 3, rng);
    EXPECT_TRUE(certified(p, solve_care(p.A, p.B, p.Q, p.R).P)) << p.name;
  }
  // The paper's Q weighs the stabilizer bar not at all: Q + PGP is still far from singular.
  const CareProblem paper = bench::paper_care_problem();
  EXPECT_TRUE(certified(paper, solve_care(paper.A, paper.B, paper.Q, paper.R).P));
}

TEST(LyapunovCertificate, NeverHoldsWhereItCannot) {
  // ẋ = x + u, Q = R = 1: the CARE 2P − P² + 1 = 0 has P = 1 ± √2; 1 − √2 leaves the closed loop
  // at √2 (and P ≺ 0).
  CareProblem scalar{"scalar", MatrixXd::Constant(1, 1, 1.0), MatrixXd::Constant(1, 1, 1.0),
                     MatrixXd::Constant(1, 1, 1.0), MatrixXd::Constant(1, 1, 1.0)};
  const auto at = [&](double p) { return certified(scalar, MatrixXd::Constant(1, 1, p)); };
  EXPECT_TRUE(at(1.0 + std::sqrt(2.0)));
  EXPECT_FALSE(at(1.0 - std::sqrt(2.0)));
  // P ≻ 0 but the closed loop 1 − P is unstable: only the second inequality can refuse it
  // (Q + PGP − Res = 2P(P − 1) < 0).
  EXPECT_FALSE(at(0.5));
  // P = 1 + 2⁻⁴⁰: the closed loop −2⁻⁴⁰ is stable and Q + PGP − Res = 2P(P − 1) ≈ 1.8e-12 clears
  // the margin; at P = 1 + 2⁻⁵⁰ it is ≈ 1.8e-15, stable still, but within the rounding of Res
  // (≈ 7e-15 here), where a computed sign proves nothing: the margin must refuse it.
  EXPECT_TRUE(at(1.0 + std::ldexp(1.0, -40)));
  EXPECT_FALSE(at(1.0 + std::ldexp(1.0, -50)));
  // Not finite: no proof (Eigen's Cholesky does not fail on NaN pivots by itself).
  EXPECT_FALSE(at(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(at(std::numeric_limits<double>::infinity()));
  // A stable plant that Q does not weigh: P = 0 stabilizes, but no P ≻ 0 shows it; the spectrum
  // must decide.
  CareProblem unweighed{"unweighed", -MatrixXd::Identity(2, 2), MatrixXd::Identity(2, 1), MatrixXd::Zero(2, 2),
                        MatrixXd::Constant(1, 1, 1.0)};
  EXPECT_FALSE(certified(unweighed, MatrixXd::Zero(2, 2)));
  // The anti-stabilizing solution of a random problem, from the stabilizing one of the equation
  // for −A (X solves it, so −X solves the original): a solution, with its closed loop unstable.
  std::mt19937_64 rng(5);
  for (const Eigen::Index n : {2, 6, 18}) {
    const CareProblem p = bench::random_care_problem("random", n, 1 + n / 3, rng);
    const MatrixXd anti = -solve_care(-p.A, p.B, p.Q, p.R).P;
    ASSERT_GT(largest_real_part(p, anti), 0.0);
    EXPECT_FALSE(certified(p, anti)) << "n = " << n;
  }
}

}  // namespace
}  // namespace thetad
