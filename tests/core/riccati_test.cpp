#include "core/riccati.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "tests/core/care_checks.hpp"
#include "tests/core/care_fixture.hpp"
#include "tests/error_message.hpp"
#include "tests/linear_algebra.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using ::testing::HasSubstr;
using testing::error_message;
using testing::kCareMethods;
using testing::scalar;
using testing::expect_valid_care;
using testing::Fixture;
using testing::read_fixture;


// The cost x'Qx + u'Ru + 2x'Nu: A'P + PA − (PB + N)R⁻¹(B'P + N') + Q = 0 and K = R⁻¹(B'P + N').
TEST(SolveCare, CrossTerm) {
  const MatrixXd A = (MatrixXd(3, 3) << 0.5, 1, 0, 0, -0.2, 1, 1, 0, 0.1).finished();
  const MatrixXd B = (MatrixXd(3, 2) << 0, 1, 1, 0, 0.5, 0.5).finished();
  const MatrixXd N = (MatrixXd(3, 2) << 0.2, 0, -0.1, 0.3, 0, 0.1).finished();
  const MatrixXd R = (MatrixXd(2, 2) << 2, 0.5, 0.5, 1).finished();
  const MatrixXd Q = N * R.llt().solve(N.transpose()) + MatrixXd::Identity(3, 3);  // Q − NR⁻¹N' = I
  const CareResult result = solve_care(A, B, Q, R, N);
  const MatrixXd coupling = B.transpose() * result.P + N.transpose();
  const MatrixXd residual = A.transpose() * result.P + result.P * A - coupling.transpose() * R.llt().solve(coupling) + Q;
  EXPECT_LE(residual.norm(), 1e-13 * result.P.norm() * A.norm());
  EXPECT_LE((R * result.K - coupling).norm(), 1e-13 * coupling.norm());
  const Eigen::VectorXcd closed_loop = testing::eigenvalues_of(A - B * result.K);
  EXPECT_LT(closed_loop.real().maxCoeff(), 0.0);
  EXPECT_THAT(error_message([&] { solve_care(A, B, Q, R, MatrixXd::Zero(2, 3)); }),
              HasSubstr("CARE: N is 2x3 but B is 3x2"));
  EXPECT_THAT(error_message([&] { solve_care(A, B, Q, -R, N); }), HasSubstr("CARE: R is not symmetric positive definite"));
}

TEST(SolveCare, DoubleIntegratorClosedForm) {
  MatrixXd A(2, 2);
  A << 0, 1, 0, 0;
  MatrixXd B(2, 1);
  B << 0, 1;
  const MatrixXd Q = MatrixXd::Identity(2, 2);
  const MatrixXd R = scalar(1);
  MatrixXd expected(2, 2);
  expected << std::sqrt(3.0), 1, 1, std::sqrt(3.0);
  for (const auto& [method, method_name] : kCareMethods) {
    const CareResult result = solve_care(A, B, Q, R, method);
    expect_valid_care(A, B, Q, R, result);
    EXPECT_LE((result.P - expected).norm(), 1e-14 * expected.norm()) << method_name;
    EXPECT_EQ(result.iterations, 0) << method_name;
  }
}

// a p + p a − p² b²/r + q = 0  ⇒  p = r (a + √(a² + b² q / r)) / b².
TEST(SolveCare, ScalarClosedForm) {
  const double cases[][4] = {{2, 1, 1, 1}, {-1, 1, 0, 1}, {-3, 0.5, 4, 2}, {10, 3, 1e4, 1e-2}, {0, 1, 1, 1}};
  for (const auto& [a, b, q, r] : cases) {
    const double expected = r * (a + std::sqrt(a * a + b * b * q / r)) / (b * b);
    for (const auto& [method, method_name] : kCareMethods) {
      const CareResult result = solve_care(scalar(a), scalar(b), scalar(q), scalar(r), method);
      expect_valid_care(scalar(a), scalar(b), scalar(q), scalar(r), result);
      EXPECT_NEAR(result.P(0, 0), expected, 1e-14 * std::max(1.0, expected))
          << method_name << ": a=" << a << " q=" << q;
    }
  }
}

TEST(SolveCare, RandomStabilizableSystems) {
  std::mt19937_64 rng(20240607);
  std::normal_distribution<double> normal;
  auto random = [&](Eigen::Index rows, Eigen::Index cols) {
    return MatrixXd(MatrixXd::NullaryExpr(rows, cols, [&]() { return normal(rng); }));
  };
  int unstable_systems = 0;
  for (int n = 1; n <= 40; ++n) {
    for (int m = 1; m <= n; ++m) {
      // Eigenvalues of randn/√n fill the unit disc; the shift makes the 1 + n % 3 (at most n) with
      // the largest real parts unstable, and perhaps a few close to them. More unstable modes on one input make the equation numerically
      // unsolvable: ‖P‖ grows like the inverse of a controllability measure that decays
      // exponentially with their number.
      MatrixXd A = random(n, n) / std::sqrt(double(n));
      VectorXd real = testing::eigenvalues_of(A).real();
      std::sort(real.begin(), real.end(), std::greater<>());
      const int unstable = std::min(n, 1 + n % 3);
      const double shift = 0.2 - real(unstable - 1);
      A += shift * MatrixXd::Identity(n, n);
      const MatrixXd B = random(n, m);
      const MatrixXd C = random(std::max(1, n / 2), n);
      const MatrixXd Q = C.transpose() * C;
      const MatrixXd M = random(m, m);
      const MatrixXd R = M * M.transpose() + 0.1 * MatrixXd::Identity(m, m);
      if (testing::max_real_eigenvalue(A) > 0) ++unstable_systems;
      SCOPED_TRACE("n=" + std::to_string(n) + " m=" + std::to_string(m));
      for (const auto& [method, method_name] : kCareMethods) {
        SCOPED_TRACE(method_name);
        expect_valid_care(A, B, Q, R, solve_care(A, B, Q, R, method));
      }
    }
  }
  EXPECT_EQ(unstable_systems, 820);
}

// The paper-sized plant at rest: A0 = F(xa(t0)), g0 = B(xa(t0)) of docs/model.md §13, weights of §7.2.
struct PaperPlant {
  MatrixXd A = MatrixXd::Zero(18, 18);
  MatrixXd B = MatrixXd::Zero(18, 5);
  MatrixXd Q = VectorXd{{1e4, 2e4, 1e7, 100, 100, 1, 100, 100, 1e3, 200, 1, 200, 1e5, 1e5, 2e3, 2e3, 1e6, 0}}.asDiagonal();
  MatrixXd R = VectorXd{{1, 200, 1e7, 1e5, 1e5}}.asDiagonal();
  PaperPlant() {
    auto a = [this](int i, int j, double v) { A(i - 1, j - 1) = v; };  // 1-based as in the spec
    a(1, 4, 1), a(2, 5, 1), a(3, 6, 1), a(4, 8, -9.81), a(5, 7, 9.81), a(5, 18, 6.3246e-6), a(6, 18, 9.84953);
    a(7, 10, 1), a(8, 11, 1), a(9, 12, 1), a(10, 14, 300), a(10, 18, 2.30496e-5), a(11, 13, 158.824);
    a(12, 18, -36.6771), a(13, 11, -1), a(13, 13, -10), a(14, 10, -1), a(14, 14, -10);
    a(15, 1, 1), a(16, 2, 1), a(17, 3, 1), a(18, 18, -0.1);
    auto g = [this](int i, int j, double v) { B(i - 1, j - 1) = v; };
    g(5, 2, 5.4), g(6, 1, -0.121951), g(10, 2, 19.68), g(12, 2, -217.810), g(13, 4, 44.515), g(14, 5, 44.515);
  }
};

// Against docs/model.md §13 the comparison is relative 2e-4, not the printed digits: our input
// is the printed (rounded) A0 and g0, and solve_care agrees with scipy on that input to 1e-11
// (checked below), yet four diag(T0) entries, the thrust feed-forward and two slow closed-loop
// eigenvalues differ from the spec by more than half a unit of its last digit:
//   T0(3,3) 736694.159 vs 736693, T0(6,6) 1888.5585 vs 1888.55, T0(8,8) 3991.2912 vs 3991.31,
//   T0(18,18) 32754.934 vs 32754.8, T0(12,12) 2.40741 vs 2.407 (1.7e-4 relative: the reason for
//   2e-4), feed-forward 80.765792 vs 80.7656: within what the rounding of the printed A0, g0
//   entries moves them (first-order: 1.5, 0.012, 1.5, 1.2, 0.019, 3.7e-4);
//   eigenvalues −0.4476615 vs −0.44770 and −0.3163068 vs −0.31630: not explained by that
//   rounding (they move by < 1e-9), so the spec's list and its A0/g0 are not quite consistent.
void expect_paper_solution(const PaperPlant& plant, const CareResult& result) {
  expect_valid_care(plant.A, plant.B, plant.Q, plant.R, result);
  EXPECT_LE(result.relative_residual, 1e-13);
  EXPECT_EQ(result.iterations, 0);
  std::cout << "paper case: relative residual " << result.relative_residual << ", " << result.sign_iterations
            << " sign iterations\n";
  constexpr double kSpec = 2e-4;

  const double diag_T0[] = {7758.9,  12453.1, 736693,  899.94,  1194.94, 1888.55, 4564.85, 3991.31,   455.93,
                            35.131,  64.12,   2.407,   2312.85, 2633.21, 5669.13, 7380.58, 3.23429e6, 32754.8};
  for (int i = 0; i < 18; ++i)
    EXPECT_NEAR(result.P(i, i), diag_T0[i], kSpec * diag_T0[i]) << "diag(T0) entry " << i + 1;

  const std::complex<double> j(0, 1);
  const std::complex<double> closed_loop[] = {
      -218.70, -41.824, -32.881, -20.231, -13.885 + 13.887 * j, -13.885 - 13.887 * j, -4.7297 + 1.5033 * j,
      -4.7297 - 1.5033 * j, -4.4291, -2.2507 + 3.8382 * j, -2.2507 - 3.8382 * j, -2.2363, -2.0500 + 4.1313 * j,
      -2.0500 - 4.1313 * j, -0.44770, -0.31630, -0.31623, -0.1};
  std::vector<bool> matched(18, false);
  for (const auto& expected : closed_loop) {
    int best = -1;
    for (int i = 0; i < 18; ++i)
      if (!matched[i] && (best < 0 || std::abs(result.closed_loop_eigenvalues(i) - expected) <
                                          std::abs(result.closed_loop_eigenvalues(best) - expected)))
        best = i;
    matched[best] = true;
    EXPECT_LE(std::abs(result.closed_loop_eigenvalues(best) - expected), kSpec * std::abs(expected))
        << "closed-loop eigenvalue " << expected << ", got " << result.closed_loop_eigenvalues(best);
  }

  // s-column feed-forward −R⁻¹g0'T0(:, 18) = −K(:, 18); the δ_col, δ_lon entries are exactly 0.
  const double feed_forward[] = {80.7656, -0.03912, 0, 0, 0.07319};
  for (int i = 0; i < 5; ++i)
    EXPECT_NEAR(-result.K(i, 17), feed_forward[i], std::max(kSpec * std::abs(feed_forward[i]), 1e-12))
        << "feed-forward " << i + 1;

  // scipy.linalg.solve_continuous_are (Debian scipy 1.10.1) on the same printed A0, g0.
  const double scipy_diag[][2] = {{2, 7.3669415875196108e+05}, {5, 1.8885584576208175e+03},
                                  {7, 3.9912912202382240e+03}, {17, 3.2754934442395432e+04}};
  for (const auto& [i, value] : scipy_diag)
    EXPECT_NEAR(result.P(int(i), int(i)), value, 1e-11 * value) << "scipy T0 entry " << i + 1;
  EXPECT_NEAR(-result.K(0, 17), 8.0765791820821363e+01, 1e-11 * 80.8);
}

TEST(SolveCare, PaperSizedCaseMatchesSpec) {
  const PaperPlant plant;
  // automatic takes the sign function here (docs/riccati.md: faster than SB02MD).
  EXPECT_GT(solve_care(plant.A, plant.B, plant.Q, plant.R).sign_iterations, 0);
  for (const auto& [method, method_name] : kCareMethods) {
    SCOPED_TRACE(method_name);
    expect_paper_solution(plant, solve_care(plant.A, plant.B, plant.Q, plant.R, method));
  }
}

// Per example: the residual tolerance for expect_valid_care and the relative distance allowed to
// the reference (the exact solution where CAREX gives one, scipy's otherwise). Where these are
// looser than 1e-10 / 1e-8 the reason is the conditioning of the example, stated alongside.
struct CarexExpectation {
  double residual_tol;
  double solution_tol;
  const char* why;
  // False where the sign iteration cannot resolve the spectrum: CareMethod::matrix_sign must
  // refuse, and automatic must hand the equation to the Schur method.
  bool sign_applies = true;
};

const std::map<std::string, CarexExpectation> kCarex = {
    {"carex_1_1", {1e-14, 1e-14, "well conditioned"}},
    {"carex_1_2", {1e-13, 1e-13, "well conditioned"}},
    {"carex_2_1", {1e-13, 1e-10, "nearly unstabilizable (eps = 1e-6), ‖P‖ = 2e12"}},
    {"carex_2_2", {1e-10, 5e-8,
                   "R nearly singular: κ(R)·u = 4.4e-8, and G = BR⁻¹B' formed from it is already 1.0e-8 off "
                   "(against 50 digits); the scipy P, from the extended pencil without R⁻¹, is within 4.5e-13 "
                   "of a 60-digit solution. Measured: Schur 8.8e-9, SB02MD 8.7e-9, sign 2.8e-8; on random "
                   "problems with such R neither method is the more accurate (docs/riccati.md)"}},
    {"carex_2_3", {1e-13, 1e-8, "ill conditioned for large eps"}},
    {"carex_2_4", {1e-13, 1e-8, "ill-conditioned Hamiltonian (eps = 1e-7)"}},
    {"carex_2_6", {1e-12, 1e-8, "badly scaled Hamiltonian, scipy is off by 2e-3 here: compared to X_exact"}},
    {"carex_2_7", {1e-12, 1e-8, "stiff, entries 1e6"}},
    {"carex_2_8", {1e-12, 1e-3,
                   "poor separation of the closed-loop spectrum: ours and scipy's normwise residuals are both at "
                   "rounding level (~1e-16), yet they differ by 3e-4; a Hamiltonian eigenvalue at Re λ = 5e-13",
                   false}},
    {"carex_3_1", {1e-12, 1e-8, "n = 39"}},
    {"carex_3_2", {1e-12, 1e-12, "n = 64, exact solution known"}},
    {"carex_4_1", {1e-12, 1e-6, "ill-conditioned Riccati equation, n = 21: normwise residuals of ours and "
                                "scipy's are both ~1e-16, they differ by 1.2e-7"}},
};

TEST(SolveCare, CarexBenchmarks) {
  const std::filesystem::path dir = std::filesystem::path(THETAD_SOURCE_DIR) / "tests/fixtures/carex";
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), kCarex.size()) << "fixtures and expectations out of step";
  for (const auto& path : files) {
    const Fixture f = read_fixture(path);
    SCOPED_TRACE(f.name);
    ASSERT_TRUE(kCarex.count(f.name)) << "no expectation for " << f.name;
    const CarexExpectation& expect = kCarex.at(f.name);
    const MatrixXd& A = f.matrices.at("A");
    const MatrixXd& B = f.matrices.at("B");
    const MatrixXd& Q = f.matrices.at("Q");
    const MatrixXd& R = f.matrices.at("R");
    const bool exact = f.matrices.count("X_exact") > 0;
    const MatrixXd& reference = exact ? f.matrices.at("X_exact") : f.matrices.at("P");
    for (const auto& [method, method_name] : kCareMethods) {
      SCOPED_TRACE(method_name);
      if (!expect.sign_applies && method == CareMethod::matrix_sign) {
        EXPECT_THROW(solve_care(A, B, Q, R, method), Error);
        continue;
      }
      const CareResult result = solve_care(A, B, Q, R, method);
      if (!expect.sign_applies) {
        EXPECT_EQ(result.sign_iterations, 0) << "automatic did not fall back to Schur";
      }
      expect_valid_care(A, B, Q, R, result, expect.residual_tol);
      const double distance = (result.P - reference).norm() / reference.norm();
      const double to_scipy = (result.P - f.matrices.at("P")).norm() / f.matrices.at("P").norm();
      EXPECT_LE(distance, expect.solution_tol) << expect.why;
      std::cout << f.name << " " << method_name << ": " << result.sign_iterations << " sign iterations, "
                << result.iterations << " refinement steps, relative residual " << result.relative_residual
                << ", relative distance to " << (exact ? "exact" : "scipy") << " " << distance << ", to scipy "
                << to_scipy << "\n";
    }
  }
}

TEST(SolveCare, StableUncontrollableModeWithZeroWeightIsFine) {
  // Stabilizable and detectable but neither controllable nor observable: the s-mode situation.
  MatrixXd A(2, 2);
  A << 1, 0, 0, -0.1;
  MatrixXd B(2, 1);
  B << 1, 0;
  MatrixXd Q = MatrixXd::Zero(2, 2);
  Q(0, 0) = 1;
  const CareResult result = solve_care(A, B, Q, scalar(1));
  expect_valid_care(A, B, Q, scalar(1), result);
  EXPECT_NEAR(result.P(0, 0), 1 + std::sqrt(2.0), 1e-14);
  EXPECT_EQ(result.P(1, 1), 0.0);
}

}  // namespace
}  // namespace thetad
