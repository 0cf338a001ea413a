// Riccati and Lyapunov solvers: thetad against SLICOT SB02MD and against the alternative ways
// of solving the θ–D Lyapunov equations, on the same problems in the same process.
// docs/performance.md explains the rows and records a run.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bench/slicot.hpp"
#include "core/lapack.hpp"
#include "core/lyapunov.hpp"
#include "core/riccati.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using MatrixRef = Eigen::Ref<const MatrixXd>;

// One Riccati problem and everything derived from it that the timed loops must not pay for.
struct Problem {
  std::string name;
  MatrixXd A, B, Q, R;
  MatrixXd P;       // solve_care(A, B, Q, R)
  MatrixXd P_warm;  // the solution for A with every entry perturbed by 1e-3 (relative)
  MatrixXd Ac;      // A − BK: the constant coefficient of the θ–D Lyapunov equations
  MatrixXd W;       // a symmetric right side shaped like θ–D's W1 = −(P Ã + Ã'P)
  std::shared_ptr<const thetad::ConstantLyapunovSolver> lyapunov;
};

MatrixXd random_normal(Index rows, Index cols, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  MatrixXd M(rows, cols);
  for (Index j = 0; j < cols; ++j)
    for (Index i = 0; i < rows; ++i) M(i, j) = normal(rng);
  return M;
}

// Diagonal weights 10^e, e uniform in [0, 7]: the paper's Q and R span the same seven decades.
MatrixXd random_weights(Index n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> exponent(0.0, 7.0);
  Eigen::VectorXd w(n);
  for (Index i = 0; i < n; ++i) w(i) = std::pow(10.0, exponent(rng));
  return w.asDiagonal();
}

MatrixXd symmetric_part(const MatrixRef& M) { return 0.5 * (M + M.transpose()); }

// ‖A'P + PA − PGP + Q‖_F / max(1, ‖Q‖_F), the normalisation of CareResult::relative_residual,
// computed here the same way for every solver.
double care_residual(const Problem& p, const MatrixRef& P) {
  const MatrixXd G = p.B * p.R.llt().solve(p.B.transpose());
  return (p.A.transpose() * P + P * p.A - P * G * P + p.Q).norm() / std::max(1.0, p.Q.norm());
}

double lyapunov_residual(const Problem& p, const MatrixRef& X) {
  return (p.Ac.transpose() * X + X * p.Ac + p.W).norm() / p.W.norm();
}

void complete(Problem& p, std::mt19937_64& rng) {
  const thetad::CareResult care = thetad::solve_care(p.A, p.B, p.Q, p.R);
  p.P = care.P;
  p.Ac = p.A - p.B * care.K;
  const MatrixXd A_near = p.A + 1e-3 * p.A.cwiseProduct(random_normal(p.A.rows(), p.A.cols(), rng));
  p.P_warm = thetad::solve_care(A_near, p.B, p.Q, p.R).P;
  const MatrixXd E = random_normal(p.A.rows(), p.A.cols(), rng);
  p.W = symmetric_part(-(p.P * E + E.transpose() * p.P));
  p.lyapunov = std::make_shared<const thetad::ConstantLyapunovSolver>(p.Ac);
}

// A random, generically controllable pair with some unstable modes.
Problem random_problem(Index n, Index m) {
  std::mt19937_64 rng(1000 * static_cast<std::uint64_t>(n) + static_cast<std::uint64_t>(m));
  Problem p;
  p.name = "n" + std::to_string(n) + "_m" + std::to_string(m);
  p.A = random_normal(n, n, rng) / std::sqrt(static_cast<double>(n));
  p.B = random_normal(n, m, rng);
  p.Q = random_weights(n, rng);
  p.R = random_weights(m, rng);
  complete(p, rng);
  return p;
}

// The helicopter at rest (paper-spec §10.3: A0, g0) with the paper's weights (§7.2).
Problem paper_problem() {
  std::mt19937_64 rng(2011);
  Problem p;
  p.name = "paper_n18_m5";
  p.A = MatrixXd::Zero(18, 18);
  const auto a = [&](int i, int j, double v) { p.A(i - 1, j - 1) = v; };
  a(1, 4, 1); a(2, 5, 1); a(3, 6, 1); a(4, 8, -9.81); a(5, 7, 9.81); a(5, 18, 6.3246e-6);
  a(6, 18, 9.84953); a(7, 10, 1); a(8, 11, 1); a(9, 12, 1); a(10, 14, 300);
  a(10, 18, 2.30496e-5); a(11, 13, 158.824); a(12, 18, -36.6771); a(13, 11, -1);
  a(13, 13, -10); a(14, 10, -1); a(14, 14, -10); a(15, 1, 1); a(16, 2, 1); a(17, 3, 1);
  a(18, 18, -0.1);
  p.B = MatrixXd::Zero(18, 5);
  const auto g = [&](int i, int j, double v) { p.B(i - 1, j - 1) = v; };
  g(5, 2, 5.4); g(6, 1, -0.121951); g(10, 2, 19.68); g(12, 2, -217.810); g(13, 4, 44.515);
  g(14, 5, 44.515);
  Eigen::VectorXd q(18);
  q << 1e4, 2e4, 1e7, 100, 100, 1, 100, 100, 1e3, 200, 1, 200, 1e5, 1e5, 2e3, 2e3, 1e6, 0;
  p.Q = q.asDiagonal();
  p.R = Eigen::Vector<double, 5>(1, 200, 1e7, 1e5, 1e5).asDiagonal();
  complete(p, rng);
  return p;
}

// ---- Riccati ---------------------------------------------------------------------------------

void bm_solve_care(benchmark::State& state, const Problem& p) {
  thetad::CareResult result;
  for (auto _ : state) {
    result = thetad::solve_care(p.A, p.B, p.Q, p.R);
    benchmark::DoNotOptimize(result.P.data());
  }
  state.counters["residual"] = care_residual(p, result.P);
}

void bm_solve_care_newton(benchmark::State& state, const Problem& p) {
  thetad::CareResult result;
  for (auto _ : state) {
    result = thetad::solve_care_newton(p.A, p.B, p.Q, p.R, p.P_warm);
    benchmark::DoNotOptimize(result.P.data());
  }
  state.counters["residual"] = care_residual(p, result.P);
  state.counters["iterations"] = result.iterations;
}

// SB02MD with its workspace allocated once outside the loop (a generous LDWORK, not the
// minimum 6N, so DGEES runs blocked). Inside the loop: what a caller holding (A, B, Q, R) must
// do, i.e. form G = B R⁻¹ B' (Cholesky of R), copy A, G and Q into the Fortran arrays (SB02MD
// overwrites Q with X) and call it. General scaling (SCAL = 'G'), stable eigenvalues first.
void bm_sb02md(benchmark::State& state, const Problem& p) {
  const int n = static_cast<int>(p.A.rows());
  const int n2 = 2 * n;
  const int ldwork = 6 * n + 64 * n2;
  MatrixXd a(n, n), g(n, n), x(n, n), s(n2, n2), u(n2, n2);
  Eigen::VectorXd wr(n2), wi(n2), dwork(ldwork);
  std::vector<int> iwork(n2), bwork(n2);
  double rcond = 0.0;
  int info = 0;
  for (auto _ : state) {
    g = p.B * p.R.llt().solve(p.B.transpose());
    a = p.A;
    x = p.Q;
    sb02md_("C", "D", "U", "G", "S", &n, a.data(), &n, g.data(), &n, x.data(), &n, &rcond,
            wr.data(), wi.data(), s.data(), &n2, u.data(), &n2, iwork.data(), dwork.data(),
            &ldwork, bwork.data(), &info, 1, 1, 1, 1, 1);
    benchmark::DoNotOptimize(x.data());
  }
  if (info != 0) {
    state.SkipWithError(("SB02MD info " + std::to_string(info)).c_str());
    return;
  }
  state.counters["residual"] = care_residual(p, x);
  state.counters["rcond"] = rcond;
}

// ---- Lyapunov: the θ–D equation Ac'X + XAc + W = 0 with constant Ac ------------------------

void bm_constant_lyapunov(benchmark::State& state, const Problem& p) {
  MatrixXd X(p.W.rows(), p.W.cols());
  for (auto _ : state) {
    p.lyapunov->solve(p.W, X);
    benchmark::DoNotOptimize(X.data());
  }
  state.counters["residual"] = lyapunov_residual(p, X);
  state.counters["condition"] = p.lyapunov->condition_number();
}

void bm_solve_lyapunov(benchmark::State& state, const Problem& p) {
  MatrixXd X;
  for (auto _ : state) {
    X = thetad::solve_lyapunov(p.Ac, p.W);
    benchmark::DoNotOptimize(X.data());
  }
  state.counters["residual"] = lyapunov_residual(p, X);
}

// The alternatives ConstantLyapunovSolver was chosen against, each with its precomputation
// outside the loop and its buffers preallocated.

// The paper's form (spec §5.6): vec(X) = −𝒜⁻¹ vec(W), 𝒜 = I ⊗ Ac' + Ac' ⊗ I, n² unknowns.
void bm_alt_kronecker_inverse(benchmark::State& state, const Problem& p) {
  const Index n = p.Ac.rows();
  const MatrixXd I = MatrixXd::Identity(n, n);
  const MatrixXd At = p.Ac.transpose();
  MatrixXd kron(n * n, n * n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j)
      kron.block(i * n, j * n, n, n) = I(i, j) * At + At(i, j) * I;
  const MatrixXd inverse = -kron.partialPivLu().inverse();
  MatrixXd X(n, n);
  for (auto _ : state) {
    Eigen::Map<Eigen::VectorXd>(X.data(), n * n).noalias() =
        inverse * Eigen::Map<const Eigen::VectorXd>(p.W.data(), n * n);
    benchmark::DoNotOptimize(X.data());
  }
  state.counters["residual"] = lyapunov_residual(p, X);
}

// The symmetric half (n(n+1)/2 unknowns) with an LU factorisation instead of the inverse.
void bm_alt_packed_lu(benchmark::State& state, const Problem& p) {
  const Index n = p.Ac.rows();
  const Index m = n * (n + 1) / 2;
  const auto index = [](Index i, Index j) { return j * (j + 1) / 2 + i; };
  MatrixXd op(m, m);
  for (Index l = 0; l < n; ++l)
    for (Index k = 0; k <= l; ++k) {
      MatrixXd E = MatrixXd::Zero(n, n);
      E(k, l) = E(l, k) = 1.0;
      const MatrixXd image = p.Ac.transpose() * E + E * p.Ac;
      for (Index j = 0; j < n; ++j)
        for (Index i = 0; i <= j; ++i) op(index(i, j), index(k, l)) = image(i, j);
    }
  const Eigen::PartialPivLU<MatrixXd> lu(op);
  Eigen::VectorXd w(m), x(m);
  MatrixXd X(n, n);
  for (auto _ : state) {
    for (Index j = 0; j < n; ++j)
      for (Index i = 0; i <= j; ++i) w(index(i, j)) = -p.W(i, j);
    x = lu.solve(w);
    for (Index j = 0; j < n; ++j)
      for (Index i = 0; i <= j; ++i) X(i, j) = X(j, i) = x(index(i, j));
    benchmark::DoNotOptimize(X.data());
  }
  state.counters["residual"] = lyapunov_residual(p, X);
}

// Bartels–Stewart with the real Schur form Ac = U T U' computed once: per solve two n×n
// similarity transforms and one quasi-triangular Sylvester solve (LAPACK dtrsyl).
void bm_alt_schur_precomputed(benchmark::State& state, const Problem& p) {
  const auto n = static_cast<lapack_int>(p.Ac.rows());
  MatrixXd T = p.Ac, U(n, n);
  Eigen::VectorXd wr(n), wi(n);
  lapack_int sdim = 0;
  if (LAPACKE_dgees(LAPACK_COL_MAJOR, 'V', 'N', nullptr, n, T.data(), n, &sdim, wr.data(),
                    wi.data(), U.data(), n) != 0)
    throw std::runtime_error("dgees failed");
  MatrixXd Y(n, n), work(n, n), X(n, n);
  double scale = 1.0;
  for (auto _ : state) {
    work.noalias() = U.transpose() * p.W;
    Y.noalias() = -work * U;
    LAPACKE_dtrsyl(LAPACK_COL_MAJOR, 'T', 'N', 1, n, n, T.data(), n, T.data(), n, Y.data(), n,
                   &scale);
    work.noalias() = U * Y;
    X.noalias() = work * U.transpose();
    benchmark::DoNotOptimize(X.data());
  }
  state.counters["residual"] = lyapunov_residual(p, X);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  // Static storage: the benchmarks hold references to the problems until the end of main.
  static std::vector<Problem> problems;
  problems.push_back(paper_problem());
  for (const auto& [n, m] : {std::pair<Index, Index>{6, 2}, {12, 4}, {18, 5}, {36, 10}})
    problems.push_back(random_problem(n, m));

  using Function = void (*)(benchmark::State&, const Problem&);
  const std::pair<const char*, Function> every_size[] = {
      {"solve_care", bm_solve_care},
      {"solve_care_newton_warm", bm_solve_care_newton},
      {"sb02md", bm_sb02md},
      {"constant_lyapunov_solve", bm_constant_lyapunov},
      {"solve_lyapunov", bm_solve_lyapunov},
  };
  // The n² Kronecker operator is 1296×1296 at n = 36: its setup alone would dominate a run.
  const std::pair<const char*, Function> up_to_18[] = {
      {"alt_lyapunov_kronecker_inverse", bm_alt_kronecker_inverse},
      {"alt_lyapunov_packed_lu", bm_alt_packed_lu},
      {"alt_lyapunov_schur_precomputed", bm_alt_schur_precomputed},
  };
  for (const Problem& p : problems) {
    for (const auto& [name, function] : every_size)
      benchmark::RegisterBenchmark((std::string(name) + "/" + p.name).c_str(), function, p)
          ->Unit(benchmark::kMicrosecond);
    if (p.A.rows() <= 18)
      for (const auto& [name, function] : up_to_18)
        benchmark::RegisterBenchmark((std::string(name) + "/" + p.name).c_str(), function, p)
            ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
