// Newton–Kleinman: converges from warm starts near and far from the solution, and what it reports
// is the truth about the P it returns (issue 16): relative_residual is the residual of that P by
// the documented formula, and the iteration reaches its tolerance on the residual of that P
// or says it did not. Every refusal of solve_care holds for this entry point too.
#include "core/newton_kleinman.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bench/care_problems.hpp"
#include "core/error.hpp"
#include "core/machine_epsilon.hpp"
#include "core/riccati.hpp"
#include "tests/core/care_checks.hpp"
#include "tests/error_message.hpp"
#include "tests/linear_algebra.hpp"

namespace thetad {
namespace {

using bench::CareProblem;
using Eigen::MatrixXd;
using ::testing::AllOf;
using ::testing::AnyOf;
using ::testing::HasSubstr;
using testing::error_message;
using testing::scalar;
using testing::expect_valid_care;

// The documented formula, evaluated here independently of the solver, in long double with G
// formed explicitly. Not in double: there, forming G = B R⁻¹ B' and P G P loses what the residual
// is made of. On random_n40 below, the residual of Newton–Kleinman's P is 4.9e-13 (checked in
// 50-digit arithmetic, scripts/care_reference.py's mpmath), solve_care_newton reports 5.4e-13, and
// the double evaluation with explicit G gives 1.5e-9: the "8.5e-8" of issue 16 was that
// evaluation, not the solver's report.
struct Residual {
  double relative;  // ‖Res‖_F / max(1, ‖Q‖_F)
  double to_terms;  // ρ = ‖Res‖_F / (‖Q‖_F + 2‖A'P‖_F + ‖PGP‖_F)
  // What evaluating the formula in double may get wrong, relative to max(1, ‖Q‖_F): the
  // componentwise bound n·eps·(|Q| + 2|A'||P| + |P||B||R⁻¹||B'||P|) in the Frobenius norm.
  double rounding;
};

using Long = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

// Every long-double product goes through this one function, on plain matrices: each distinct
// Eigen product expression (a chain of five products of |·| views) is its own instantiation of
// the GEMM machinery, and GCC's overload resolution over such chains took ~20 s of this file's
// compile (docs/performance-log.md, 2026-12-02). The same products, in the same order.
Long times(const Long& X, const Long& Y) { return X * Y; }

Residual residual_of(const CareProblem& p, const MatrixXd& P_double) {
  const Long A = p.A.cast<long double>(), B = p.B.cast<long double>(), Q = p.Q.cast<long double>();
  const Long P = P_double.cast<long double>();
  const Long R_inverse = p.R.cast<long double>().inverse();
  const Long At = A.transpose(), Bt = B.transpose();
  const Long G = times(times(B, R_inverse), Bt);
  const Long AtP = times(At, P);
  const Long PGP = times(times(P, G), P);
  const long double res = (AtP + AtP.transpose() - PGP + Q).norm();
  const long double terms = Q.norm() + 2.0L * AtP.norm() + PGP.norm();
  const Long abs_P = P.cwiseAbs(), abs_B = B.cwiseAbs(), abs_Bt = Bt.cwiseAbs();
  const Long absolute = Q.cwiseAbs() + 2.0L * times(At.cwiseAbs(), abs_P) +
                        times(times(times(times(abs_P, abs_B), R_inverse.cwiseAbs()), abs_Bt), abs_P);
  // In long double too: its exponent range holds the squares of weights scaled by 1e±300.
  const long double q_scale = std::max(1.0L, Q.norm());
  return {static_cast<double>(res / q_scale), static_cast<double>(res / terms),
          static_cast<double>(static_cast<long double>(p.A.rows()) * kEps * absolute.norm() / q_scale)};
}

bool stabilizes(const CareProblem& p, const MatrixXd& P) {
  const MatrixXd Ac = p.A - p.B * p.R.llt().solve(p.B.transpose() * P);
  return testing::max_real_eigenvalue(Ac) < 0.0;
}

// The problems: the paper's, the paper's with every rate 18 times faster (A·18: the one the issue
// saw report 5e-12 for a P whose residual was 8.5e-8), and random ones with the paper's weight
// spread up to n = 40.
std::vector<CareProblem> problems() {
  std::vector<CareProblem> all{bench::paper_care_problem()};
  CareProblem fast = bench::paper_care_problem();
  fast.name = "paper_A_times_18";
  fast.A *= 18.0;
  all.push_back(fast);
  std::mt19937_64 rng(16);
  for (const auto& [n, m] : {std::pair{6, 2}, {18, 5}, {40, 13}})
    all.push_back(bench::random_care_problem("random_n" + std::to_string(n), n, m, rng));
  return all;
}

// P ∘ (1 + δS) with S symmetric, entries uniform in [−1, 1].
MatrixXd perturbed(const MatrixXd& P, double delta, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  MatrixXd S = MatrixXd::NullaryExpr(P.rows(), P.cols(), [&] { return unit(rng); });
  S = 0.5 * (S + S.transpose()).eval();
  return P.cwiseProduct(MatrixXd::Ones(P.rows(), P.cols()) + delta * S);
}

void expect_honest(const CareProblem& p, const CareResult& result, double tolerance) {
  expect_valid_care(p.A, p.B, p.Q, p.R, result);
  const Residual truth = residual_of(p, result.P);
  // The reported residual is the one of the returned P, to the rounding of evaluating it.
  EXPECT_NEAR(result.relative_residual, truth.relative, truth.rounding);
  // The tolerance is met on the P returned, not on an earlier iterate.
  EXPECT_LE(truth.to_terms, tolerance + 64.0 * kEps);
}

// From P0 = (1 ± δ)P: stabilizing for δ ≤ 1/2 (the LQR gain margin), on every problem; and on the
// paper's problems from P ∘ (1 + δS), S symmetric random, which moves every entry independently.
TEST(NewtonKleinman, WarmStartsFromPerturbedSolutionsReachTheToleranceOnTheReturnedP) {
  std::mt19937_64 rng(1016);
  for (const CareProblem& p : problems()) {
    const MatrixXd P = solve_care(p.A, p.B, p.Q, p.R).P;
    const bool paper = p.name.rfind("paper", 0) == 0;
    for (const double delta : {1e-3, 1e-1}) {
      std::vector<std::pair<std::string, MatrixXd>> starts{{"(1 + δ)P", (1.0 + delta) * P},
                                                           {"(1 − δ)P", (1.0 - delta) * P}};
      if (paper) starts.emplace_back("P ∘ (1 + δS)", perturbed(P, delta, rng));
      for (const auto& [how, P0] : starts) {
        SCOPED_TRACE(p.name + " from " + how + ", δ = " + std::to_string(delta));
        ASSERT_TRUE(stabilizes(p, P0)) << "the test needs a stabilizing warm start";
        const CareResult result = solve_care_newton(p.A, p.B, p.Q, p.R, P0);
        expect_honest(p, result, 1e-12);
        EXPECT_GE(result.iterations, 1);
        EXPECT_LE(result.iterations, 12);
        // The same solution as the direct solver, to the conditioning of the problem.
        EXPECT_LE((result.P - P).norm(), 1e-8 * P.norm());
      }
    }
  }
}

TEST(NewtonKleinman, ConvergesFromNearbySystem) {
  const CareProblem plant = bench::paper_care_problem();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> sign(-1.0, 1.0);
  MatrixXd nearby = plant.A;
  for (Eigen::Index i = 0; i < nearby.size(); ++i) nearby(i) *= 1.0 + 1e-3 * sign(rng);
  const CareResult warm = solve_care(nearby, plant.B, plant.Q, plant.R);
  const CareResult direct = solve_care(plant.A, plant.B, plant.Q, plant.R);
  const CareResult newton = solve_care_newton(plant.A, plant.B, plant.Q, plant.R, warm.P);
  expect_valid_care(plant.A, plant.B, plant.Q, plant.R, newton);
  EXPECT_LE(newton.iterations, 6);
  EXPECT_GE(newton.iterations, 1);
  EXPECT_LE((newton.P - direct.P).norm(), 1e-10 * direct.P.norm());
  std::cout << "Newton from nearby system: " << newton.iterations << " iterations, relative residual "
            << newton.relative_residual << ", distance to Laub " << (newton.P - direct.P).norm() / direct.P.norm()
            << "\n";
}

TEST(NewtonKleinman, ConvergesOnRandomSystems) {
  std::mt19937_64 rng(99);
  std::normal_distribution<double> normal;
  auto random = [&](Eigen::Index rows, Eigen::Index cols) {
    return MatrixXd(MatrixXd::NullaryExpr(rows, cols, [&]() { return normal(rng); }));
  };
  for (int n : {1, 3, 8, 18, 30}) {
    const int m = std::max(1, n / 3);
    const MatrixXd A = random(n, n) / std::sqrt(double(n)) + 0.3 * MatrixXd::Identity(n, n);
    const MatrixXd B = random(n, m);
    const MatrixXd Q = MatrixXd::Identity(n, n);
    const MatrixXd R = MatrixXd::Identity(m, m);
    const MatrixXd nearby = A + 1e-3 * A.norm() / n * random(n, n);
    const CareResult warm = solve_care(nearby, B, Q, R);
    const CareResult newton = solve_care_newton(A, B, Q, R, warm.P);
    SCOPED_TRACE("n=" + std::to_string(n));
    expect_valid_care(A, B, Q, R, newton);
    EXPECT_LE(newton.iterations, 6);
    EXPECT_LE((newton.P - solve_care(A, B, Q, R).P).norm(), 1e-10 * newton.P.norm());
  }
}

TEST(NewtonKleinman, WarmStartFromANearbySystemOfEverySize) {
  std::mt19937_64 rng(99);
  for (const CareProblem& p : problems()) {
    SCOPED_TRACE(p.name);
    const MatrixXd nearby = p.A + 1e-3 * p.A.cwiseProduct(bench::random_normal(p.A.rows(), p.A.cols(), rng));
    const MatrixXd P0 = solve_care(nearby, p.B, p.Q, p.R).P;
    const CareResult result = solve_care_newton(p.A, p.B, p.Q, p.R, P0);
    expect_honest(p, result, 1e-12);
    EXPECT_LE(result.iterations, 8);
  }
}

TEST(NewtonKleinman, AnExactStartTakesOneStepAndStays) {
  const CareProblem p = bench::paper_care_problem();
  const CareResult direct = solve_care(p.A, p.B, p.Q, p.R);
  const CareResult result = solve_care_newton(p.A, p.B, p.Q, p.R, direct.P, 1e-10);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_LE((result.P - direct.P).norm(), 1e-12 * direct.P.norm());
  expect_honest(p, result, 1e-10);
}

TEST(NewtonKleinman, ATighterToleranceThanRoundingAllowsIsReportedNotFaked) {
  const CareProblem p = bench::paper_care_problem();
  const MatrixXd P0 = 1.5 * solve_care(p.A, p.B, p.Q, p.R).P;
  EXPECT_THAT(error_message([&] { solve_care_newton(p.A, p.B, p.Q, p.R, P0, 1e-20); }),
              AllOf(AnyOf(HasSubstr("Newton–Kleinman stalled above the tolerance"), HasSubstr("did not converge")),
                    HasSubstr("residual ρ"), HasSubstr("tolerance 1e-20")));
}

TEST(NewtonKleinman, OneSolverServesManyEquationsWithTheSameWeights) {
  const CareProblem p = bench::paper_care_problem();
  NewtonKleinmanSolver solver(p.Q, p.R);
  MatrixXd P = solve_care(p.A, p.B, p.Q, p.R).P;
  std::mt19937_64 rng(3);
  for (int k = 0; k < 5; ++k) {
    CareProblem next = p;
    next.A += 1e-2 * p.A.cwiseProduct(bench::random_normal(p.A.rows(), p.A.cols(), rng));
    const CareResult& result = solver.solve(next.A, next.B, P);
    expect_honest(next, result, solver.tolerance());
    EXPECT_NEAR(solver.last_residual_to_terms(), residual_of(next, result.P).to_terms, 64.0 * kEps);
    P = result.P;
  }
}

// With a Schur form held from an earlier solve, a warm start far away (every entry of A moved by
// up to ~20 %) begins with chord steps; one that raises the residual is undone and taken again as
// a Newton step. It was taken again as the same chord step until the iteration budget ran out, and
// the restart from P0 had no budget left: this sequence threw "did not converge in 50 iterations".
TEST(NewtonKleinman, AnUndoneChordStepIsTakenAgainAsANewtonStep) {
  const CareProblem p = bench::paper_care_problem();
  NewtonKleinmanSolver solver(p.Q, p.R);
  MatrixXd P = solve_care(p.A, p.B, p.Q, p.R).P;
  solver.solve(p.A, p.B, P);
  std::mt19937_64 rng(1);
  for (int k = 0; k < 2; ++k) {
    CareProblem next = p;
    next.A += 0.2 * p.A.cwiseProduct(bench::random_normal(p.A.rows(), p.A.cols(), rng));
    const CareResult& result = solver.solve(next.A, next.B, P);
    expect_honest(next, result, solver.tolerance());
    EXPECT_LE(result.iterations, 20);
    P = result.P;
  }
}

// StabilityProof::lyapunov: the same solutions as with the spectrum, to the tolerance, with fewer
// Schur forms (the certificate replaces the final one, and the held Schur form is that of the last
// Newton step); the eigenvalues it did not compute are NaN, never stale.
TEST(NewtonKleinman, TheLyapunovCertificateSparesSchurFormsAndReportsNoEigenvalues) {
  const CareProblem p = bench::paper_care_problem();
  NewtonKleinmanSolver by_spectrum(p.Q, p.R);
  NewtonKleinmanSolver by_certificate(p.Q, p.R, 1e-12, 50, StabilityProof::lyapunov);
  MatrixXd P = solve_care(p.A, p.B, p.Q, p.R).P;
  std::mt19937_64 rng(4);
  int spectrum_forms = 0, certificate_forms = 0;
  for (int k = 0; k < 8; ++k) {
    CareProblem next = p;
    next.A += 1e-4 * p.A.cwiseProduct(bench::random_normal(p.A.rows(), p.A.cols(), rng));
    const MatrixXd reference = by_spectrum.solve(next.A, next.B, P).P;
    spectrum_forms += by_spectrum.last_schur_forms();
    CareResult result = by_certificate.solve(next.A, next.B, P);
    certificate_forms += by_certificate.last_schur_forms();
    EXPECT_TRUE(by_certificate.last_certified()) << "call " << k;
    EXPECT_TRUE(result.closed_loop_eigenvalues.array().isNaN().all()) << "call " << k;
    EXPECT_LE((result.P - reference).norm(), 1e-10 * reference.norm()) << "call " << k;
    EXPECT_LE(residual_of(next, result.P).to_terms, by_certificate.tolerance() + 64.0 * kEps);
    // Every other property of a solution, with the spectrum recomputed here.
    result.closed_loop_eigenvalues = testing::eigenvalues_of(next.A - next.B * result.K);
    expect_valid_care(next.A, next.B, next.Q, next.R, result);
    P = result.P;
  }
  EXPECT_LT(certificate_forms, spectrum_forms);
  EXPECT_FALSE(by_spectrum.last_certified());
}

// Where no certificate can hold, the spectrum decides and is reported: a stable mode that Q does
// not weigh has P = 0 there, so P is singular. Two decoupled modes, B = R = I: ẋ1 = −x1 + u1 with
// q1 = 0 (p1 = 0, closed loop −1), ẋ2 = x2 + u2 with q2 = 1 (p2 = 1 + √2, closed loop −√2).
// From p1 = 0 the iteration leaves p1 at exactly 0 (its residual is exactly 0).
TEST(NewtonKleinman, WithoutACertificateTheSpectrumDecides) {
  const MatrixXd A = Eigen::Vector2d(-1.0, 1.0).asDiagonal();
  const MatrixXd I2 = MatrixXd::Identity(2, 2);
  const MatrixXd Q = Eigen::Vector2d(0.0, 1.0).asDiagonal();
  NewtonKleinmanSolver solver(Q, I2, 1e-12, 50, StabilityProof::lyapunov);
  const MatrixXd P0 = Eigen::Vector2d(0.0, 3.0).asDiagonal();
  const CareResult& result = solver.solve(A, I2, P0);
  EXPECT_FALSE(solver.last_certified());
  EXPECT_EQ(result.P(0, 0), 0.0);
  EXPECT_NEAR(result.P(1, 1), 1.0 + std::sqrt(2.0), 1e-12);
  std::vector<double> eigenvalues{result.closed_loop_eigenvalues(0).real(), result.closed_loop_eigenvalues(1).real()};
  std::sort(eigenvalues.begin(), eigenvalues.end());
  EXPECT_NEAR(eigenvalues[0], -std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(eigenvalues[1], -1.0, 1e-12);
}

// The solution P = 0 (Q = 0, A stable): every term of ρ vanishes with P, so ρ stays near 1 until
// P is exactly 0. A Newton step takes p to p²/(2(1 + p)) (0.5, 0.083, …, 8.6e-23) and then to 0
// exactly, once 1 + p rounds to 1; the iteration used to divide 0 by 0 there and report "the
// residual is not finite".
TEST(NewtonKleinman, TheZeroSolutionIsReached) {
  const MatrixXd A = -MatrixXd::Identity(2, 2);
  const CareResult result = solve_care_newton(A, MatrixXd::Identity(2, 1), MatrixXd::Zero(2, 2), scalar(1),
                                              0.5 * MatrixXd::Identity(2, 2));
  EXPECT_EQ(result.P.norm(), 0.0);
  EXPECT_EQ(result.relative_residual, 0.0);
}

// (Q, R) → (sQ, sR) takes P to sP and leaves ρ as it was. From s = 1e-170 down every entry of the
// residual lies below 1e-154, where the sum of squares in Eigen's norm() underflows to 0, and from
// s = 1e200 up above 1e154, where it overflows: Newton–Kleinman used to stop at once on ρ = 0,
// returning its warm start and reporting a zero residual, or to throw "the residual is not
// finite"; the direct solvers, whose scaling of the Hamiltonian overflowed (the sign function) or
// left it unbalanced (the Schur method, already at s = 1e50), refused the equation.
TEST(NewtonKleinman, WeightsScaledToTheEndsOfTheDoubleRangeGiveTheScaledSolution) {
  const CareProblem p = bench::paper_care_problem();
  const MatrixXd P = solve_care(p.A, p.B, p.Q, p.R).P;
  for (const double s : {1e-300, 1e-170, 1e200, 1e300}) {
    SCOPED_TRACE("s = 1e" + std::to_string(std::lround(std::log10(s))));
    CareProblem scaled = p;
    scaled.Q *= s;
    scaled.R *= s;
    const MatrixXd P0 = (1.0 + 1e-3) * (s * P);
    const std::vector<std::pair<std::string, std::function<CareResult()>>> solvers{
        {"Newton–Kleinman", [&] { return solve_care_newton(scaled.A, scaled.B, scaled.Q, scaled.R, P0); }},
        {"matrix sign", [&] { return solve_care(scaled.A, scaled.B, scaled.Q, scaled.R, CareMethod::matrix_sign); }},
        {"Schur", [&] { return solve_care(scaled.A, scaled.B, scaled.Q, scaled.R, CareMethod::schur); }}};
    for (const auto& [name, solve] : solvers) {
      SCOPED_TRACE(name);
      CareResult result;
      ASSERT_NO_THROW(result = solve());
      EXPECT_LE((result.P / s - P).norm(), 1e-9 * P.norm());
      const Residual truth = residual_of(scaled, result.P);
      EXPECT_GT(result.relative_residual, 0.0);
      EXPECT_NEAR(result.relative_residual, truth.relative, truth.rounding);
      EXPECT_LE(truth.to_terms, 1e-12);
    }
  }
}

// A solution of the CARE that does not stabilize, given as P0 to a solver that holds a Schur form:
// its residual is at rounding level, so chord steps barely move it and only a proof of stability
// can refuse it; whichever way the call goes, it must end in an error, never in that solution.
TEST(NewtonKleinman, ASolutionThatDoesNotStabilizeIsNeverReturned) {
  std::mt19937_64 rng(5);
  const CareProblem p = bench::random_care_problem("random_n6", 6, 2, rng);
  const MatrixXd star = solve_care(p.A, p.B, p.Q, p.R).P;
  const MatrixXd anti = -solve_care(-p.A, p.B, p.Q, p.R).P;
  for (const StabilityProof proof : {StabilityProof::spectrum, StabilityProof::lyapunov}) {
    NewtonKleinmanSolver solver(p.Q, p.R, 1e-12, 50, proof);
    solver.solve(p.A, p.B, star);
    EXPECT_THAT(error_message([&] { solver.solve(p.A, p.B, anti); }), HasSubstr("P0 is not stabilizing"));
    // The solver is still usable: the failed call held no Schur form.
    EXPECT_LE((solver.solve(p.A, p.B, star).P - star).norm(), 1e-10 * star.norm());
  }
}

TEST(NewtonKleinman, Errors) {
  MatrixXd A(2, 2);
  A << 1, 1, 0, 2;
  const MatrixXd B = MatrixXd::Identity(2, 2);
  const MatrixXd I2 = MatrixXd::Identity(2, 2);
  EXPECT_THAT(error_message([&] { solve_care_newton(A, B, I2, I2, MatrixXd::Zero(2, 2)); }),
              AllOf(HasSubstr("P0 is not stabilizing"), HasSubstr("largest Re λ of A − G P0 is 2")));
  EXPECT_THAT(error_message([&] { solve_care_newton(A, B, I2, I2, MatrixXd::Zero(3, 3)); }),
              HasSubstr("P0 is 3x3 but A is 2x2"));
  EXPECT_THAT(error_message([&] { solve_care_newton(A, B, I2, I2, 100 * I2, 1e-12, 1); }),
              AllOf(HasSubstr("did not converge in 1 iterations"), HasSubstr("residual ρ")));
  const MatrixXd P = solve_care(A, B, I2, I2).P;
  EXPECT_THAT(error_message([&] { solve_care_newton(A, B, I2, I2, P, 0.0); }), HasSubstr("tolerance > 0"));
  MatrixXd nan = P;
  nan(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_message([&] { solve_care_newton(A, B, I2, I2, nan); }), HasSubstr("P0 has a non-finite entry"));
}

// The refusals of care_errors_test, through Newton–Kleinman: each names the failed condition and
// the measured quantity.
TEST(NewtonKleinman, RefusesProblemsWithoutAStabilizingSolution) {
  // Unstabilizable: the mode at 2 cannot be moved by B, so no P0 stabilizes.
  const MatrixXd A = Eigen::Vector2d(1.0, 2.0).asDiagonal();
  MatrixXd B(2, 1);
  B << 1, 0;
  const MatrixXd I2 = MatrixXd::Identity(2, 2);
  EXPECT_THAT(error_message([&] { solve_care_newton(A, B, I2, scalar(1), 10 * I2); }),
              HasSubstr("P0 is not stabilizing (largest Re λ of A − G P0 is 2)"));
  // A Hamiltonian eigenvalue on the imaginary axis: A = 0 with no input, so A − G P0 = 0.
  EXPECT_THAT(error_message([&] { solve_care_newton(scalar(0), scalar(0), scalar(1), scalar(1), scalar(1)); }),
              HasSubstr("P0 is not stabilizing (largest Re λ of A − G P0 is 0)"));
  // R singular and R indefinite.
  MatrixXd singular(2, 2);
  singular << 1, 1, 1, 1;
  EXPECT_THAT(error_message([&] { solve_care_newton(A, I2, I2, singular, 10 * I2); }),
              HasSubstr("R is not symmetric positive definite (min eigenvalue "));
  MatrixXd indefinite(2, 2);
  indefinite << 1, 0, 0, -2;
  EXPECT_THAT(error_message([&] { solve_care_newton(A, I2, I2, indefinite, 10 * I2); }),
              HasSubstr("R is not symmetric positive definite (min eigenvalue -2"));
}

TEST(NewtonKleinman, UndetectableOnTheImaginaryAxisIsRefused) {
  // Undamped oscillator that Q does not see: the modes ±i stay on the axis for every stabilizing
  // feedback's limit, and there is no stabilizing solution; Newton–Kleinman must not return one.
  MatrixXd A(2, 2);
  A << 0, 1, -1, 0;
  MatrixXd B(2, 1);
  B << 0, 1;
  const MatrixXd P0 = solve_care(A, B, MatrixXd::Identity(2, 2), scalar(1)).P;
  EXPECT_THAT(error_message([&] { solve_care_newton(A, B, MatrixXd::Zero(2, 2), scalar(1), P0); }),
              HasSubstr("(Q, A) is not detectable: the mode λ = 0"));
}

}  // namespace
}  // namespace thetad
