// Riccati and Lyapunov solvers: thetad against SLICOT SB02MD and against the alternative ways
// of solving the θ–D Lyapunov equations, on the same problems in the same process.
// docs/riccati.md explains the rows and records a run.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bench/care_problems.hpp"
#include "bench/slicot.hpp"
#include "core/lapack.hpp"
#include "core/care_weights.hpp"
#include "core/lyapunov.hpp"
#include "core/lyapunov_certificate.hpp"
#include "core/riccati.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using MatrixRef = Eigen::Ref<const MatrixXd>;

// One Riccati problem and everything derived from it that the timed loops must not pay for.
struct Problem : thetad::bench::CareProblem {
  MatrixXd P;       // solve_care(A, B, Q, R)
  MatrixXd P_warm;  // the solution for A with every entry perturbed by 1e-3 (relative)
  MatrixXd Ac;      // A − BK: the constant coefficient of the θ–D Lyapunov equations
  MatrixXd W;       // a symmetric right side shaped like θ–D's W1 = −(P Ã + Ã'P)
  // Up to kLyapunovRowsUpTo states only: its construction is O(n⁶), seconds at n = 60.
  std::shared_ptr<const thetad::ConstantLyapunovSolver> lyapunov;
};

constexpr Index kLyapunovRowsUpTo = 36;

using thetad::bench::random_normal;

MatrixXd symmetric_part(const MatrixRef& M) { return 0.5 * (M + M.transpose()); }

double lyapunov_residual(const Problem& p, const MatrixRef& X) {
  return (p.Ac.transpose() * X + X * p.Ac + p.W).norm() / p.W.norm();
}

Problem complete(thetad::bench::CareProblem care_problem, std::mt19937_64& rng) {
  Problem p;
  static_cast<thetad::bench::CareProblem&>(p) = std::move(care_problem);
  const thetad::CareResult care = thetad::solve_care(p.A, p.B, p.Q, p.R);
  p.P = care.P;
  p.Ac = p.A - p.B * care.K;
  const MatrixXd A_near = p.A + 1e-3 * p.A.cwiseProduct(random_normal(p.A.rows(), p.A.cols(), rng));
  p.P_warm = thetad::solve_care(A_near, p.B, p.Q, p.R).P;
  const MatrixXd E = random_normal(p.A.rows(), p.A.cols(), rng);
  p.W = symmetric_part(-(p.P * E + E.transpose() * p.P));
  if (p.A.rows() <= kLyapunovRowsUpTo) p.lyapunov = std::make_shared<const thetad::ConstantLyapunovSolver>(p.Ac);
  return p;
}

// Seeded std::mt19937_64 (seed 1000n + m): the paper's weight spread, or Q = I, R = I (name
// suffix _unit, the same A and B).
enum class Weights { paper_spread, unit };
Problem random_problem(Index n, Index m, Weights weights = Weights::paper_spread) {
  std::mt19937_64 rng(1000 * static_cast<std::uint64_t>(n) + static_cast<std::uint64_t>(m));
  // Appended piece by piece: "n" + std::to_string(n) + … draws a false -Wrestrict from GCC 12 at -O3.
  std::string name = "n";
  name += std::to_string(n);
  name += "_m";
  name += std::to_string(m);
  if (weights == Weights::unit) {
    name += "_unit";
    return complete(thetad::bench::unit_weight_care_problem(std::move(name), n, m, rng), rng);
  }
  return complete(thetad::bench::random_care_problem(std::move(name), n, m, rng), rng);
}

Problem paper_problem() {
  std::mt19937_64 rng(2011);
  return complete(thetad::bench::paper_care_problem(), rng);
}

// ---- Riccati ---------------------------------------------------------------------------------

template <thetad::CareMethod method>
void bm_solve_care(benchmark::State& state, const Problem& p) {
  thetad::CareResult result;
  for (auto _ : state) {
    result = thetad::solve_care(p.A, p.B, p.Q, p.R, method);
    benchmark::DoNotOptimize(result.P.data());
  }
  state.counters["residual"] = thetad::bench::relative_residual(p, result.P);
  state.counters["sign_iterations"] = result.sign_iterations;
}

// The same solve through a CareSolver built once, as the SDRE's cold step uses it: no allocation,
// Q and R checked once.
void bm_care_solver(benchmark::State& state, const Problem& p) {
  thetad::CareSolver solver(p.Q, p.R);
  const thetad::CareResult* result = nullptr;
  for (auto _ : state) {
    result = &solver.solve(p.A, p.B);
    benchmark::DoNotOptimize(result->P.data());
  }
  state.counters["residual"] = thetad::bench::relative_residual(p, result->P);
  state.counters["sign_iterations"] = result->sign_iterations;
}

void bm_solve_care_newton(benchmark::State& state, const Problem& p) {
  thetad::CareResult result;
  for (auto _ : state) {
    result = thetad::solve_care_newton(p.A, p.B, p.Q, p.R, p.P_warm);
    benchmark::DoNotOptimize(result.P.data());
  }
  state.counters["residual"] = thetad::bench::relative_residual(p, result.P);
  state.counters["iterations"] = result.iterations;
}

// The same solve through a NewtonKleinmanSolver built once, allocation-free with Q and R checked
// once, as the SDRE's warm step uses it except for the proof of stability: the spectrum here, the
// Lyapunov certificate there (timed on its own below; the SDRE rows of controllers_bench time it
// in use).
void bm_newton_kleinman_solver(benchmark::State& state, const Problem& p) {
  thetad::NewtonKleinmanSolver solver(p.Q, p.R);
  const thetad::CareResult* result = nullptr;
  for (auto _ : state) {
    result = &solver.solve(p.A, p.B, p.P_warm);
    benchmark::DoNotOptimize(result->P.data());
  }
  state.counters["residual"] = thetad::bench::relative_residual(p, result->P);
  state.counters["iterations"] = result->iterations;
}

// SB02MD with its workspace allocated once outside the loop. Inside the loop: what a caller
// holding (A, B, Q, R) must do, i.e. form G = B R⁻¹ B' (Cholesky of R), copy A and Q into the
// Fortran arrays (SB02MD overwrites Q with X) and call it.
void bm_sb02md(benchmark::State& state, const Problem& p) {
  thetad::bench::Sb02md sb02md(static_cast<int>(p.A.rows()));
  MatrixXd g, x;
  int info = 0;
  for (auto _ : state) {
    g = p.B * p.R.llt().solve(p.B.transpose());
    info = sb02md.solve(p.A, g, p.Q, x);
    benchmark::DoNotOptimize(x.data());
  }
  if (info != 0) {
    state.SkipWithError(("SB02MD info " + std::to_string(info)).c_str());
    return;
  }
  state.counters["residual"] = thetad::bench::relative_residual(p, x);
  state.counters["rcond"] = sb02md.rcond();
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

// The paper's form (docs/model.md §8.1): vec(X) = −𝒜⁻¹ vec(W), 𝒜 = I ⊗ Ac' + Ac' ⊗ I, n² unknowns.
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

// X with A'X + XA + W = 0 from the real Schur form A = U T U' (LAPACK dgees): T'Y + YT = −U'WU by
// LAPACK dtrsyl, X = U Y U'.
void dtrsyl_solve(const MatrixXd& T, const MatrixXd& U, const MatrixXd& W, MatrixXd& Y, MatrixXd& work, MatrixXd& X) {
  const auto n = static_cast<lapack_int>(T.rows());
  double scale = 1.0;
  work.noalias() = U.transpose() * W;
  Y.noalias() = -work * U;
  LAPACKE_dtrsyl_work(LAPACK_COL_MAJOR, 'T', 'N', 1, n, n, T.data(), n, T.data(), n, Y.data(), n, &scale);
  work.noalias() = U * Y;
  X.noalias() = work * U.transpose();
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
  for (auto _ : state) {
    dtrsyl_solve(T, U, p.W, Y, work, X);
    benchmark::DoNotOptimize(X.data());
  }
  state.counters["residual"] = lyapunov_residual(p, X);
}

// ---- Lyapunov: a new closed loop at every solve, as in a Newton–Kleinman step -------------------
// A'X + XA + W = 0 with A = Ac, the Schur form computed inside the loop ("factor_solve") or once
// outside it ("solve_factored", the cost of a chord step's solve). The product code
// (LyapunovWorkspace: Eigen's RealSchur and its own quasi-triangular sweep) against LAPACK dgees +
// dtrsyl with every workspace sized outside the loop (what LyapunovWorkspace was before).

void bm_lyapunov_factor_solve(benchmark::State& state, const Problem& p) {
  thetad::LyapunovWorkspace workspace(p.Ac.rows());
  MatrixXd X(p.W.rows(), p.W.cols());
  for (auto _ : state) {
    workspace.factor(p.Ac);
    workspace.solve(p.W, X);
    benchmark::DoNotOptimize(X.data());
  }
  state.counters["residual"] = lyapunov_residual(p, X);
}

void bm_lyapunov_solve_factored(benchmark::State& state, const Problem& p) {
  thetad::LyapunovWorkspace workspace(p.Ac.rows());
  workspace.factor(p.Ac);
  MatrixXd X(p.W.rows(), p.W.cols());
  for (auto _ : state) {
    workspace.solve(p.W, X);
    benchmark::DoNotOptimize(X.data());
  }
  state.counters["residual"] = lyapunov_residual(p, X);
}

// The proof of stability that replaces the final Schur form of the SDRE's warm step
// (lyapunov_certificate.hpp), at the solution P: to be read against lyapunov_factor_solve, whose
// Schur form it spares.
void bm_lyapunov_certificate(benchmark::State& state, const Problem& p) {
  thetad::care::Weights w = thetad::care::prepare_weights(p.Q, p.R);
  thetad::care::set_input_matrix(w, p.B);
  const MatrixXd WP = w.W * p.P;
  MatrixXd Res(p.P.rows(), p.P.cols());
  thetad::care::care_residual(p.A, w, p.P, WP, Res);
  thetad::LyapunovCertificate certificate(p.P.rows());
  bool holds = false;
  for (auto _ : state) {
    holds = certificate.proves_hurwitz(p.A, w, p.P, WP, Res);
    benchmark::DoNotOptimize(holds);
  }
  state.counters["holds"] = holds ? 1.0 : 0.0;
}

void bm_alt_lyapunov_dgees_dtrsyl(benchmark::State& state, const Problem& p) {
  const auto n = static_cast<lapack_int>(p.Ac.rows());
  MatrixXd T(n, n), U(n, n), Y(n, n), work(n, n), X(n, n);
  Eigen::VectorXd wr(n), wi(n);
  std::vector<lapack_logical> bwork(static_cast<std::size_t>(n));
  lapack_int sdim = 0;
  double optimal = 0.0;
  LAPACKE_dgees_work(LAPACK_COL_MAJOR, 'V', 'N', nullptr, n, T.data(), n, &sdim, wr.data(), wi.data(), U.data(), n,
                     &optimal, -1, bwork.data());
  Eigen::VectorXd dgees_work(std::max<Index>(static_cast<Index>(optimal), 3 * n));
  for (auto _ : state) {
    T = p.Ac;
    if (LAPACKE_dgees_work(LAPACK_COL_MAJOR, 'V', 'N', nullptr, n, T.data(), n, &sdim, wr.data(), wi.data(), U.data(),
                           n, dgees_work.data(), static_cast<lapack_int>(dgees_work.size()), bwork.data()) != 0)
      throw std::runtime_error("dgees failed");
    dtrsyl_solve(T, U, p.W, Y, work, X);
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
  // The sweep of the solve_care target (issue 16): n = 10 … 60, m = n/3.
  for (const Index n : {10, 20, 30, 40, 50, 60}) problems.push_back(random_problem(n, n / 3));
  // The same sweep with Q = I, R = I, for the direct solvers only.
  static std::vector<Problem> unit_weight_problems;
  for (const Index n : {10, 12, 18, 20, 30, 40, 50, 60})
    unit_weight_problems.push_back(random_problem(n, n / 3, Weights::unit));

  using Function = void (*)(benchmark::State&, const Problem&);
  const std::pair<const char*, Function> every_size[] = {
      {"solve_care", bm_solve_care<thetad::CareMethod::automatic>},
      {"care_solver", bm_care_solver},
      {"solve_care_schur", bm_solve_care<thetad::CareMethod::schur>},
      {"solve_care_newton_warm", bm_solve_care_newton},
      {"newton_kleinman_solver_warm", bm_newton_kleinman_solver},
      {"sb02md", bm_sb02md},
      {"solve_lyapunov", bm_solve_lyapunov},
      {"lyapunov_factor_solve", bm_lyapunov_factor_solve},
      {"lyapunov_certificate", bm_lyapunov_certificate},
      {"lyapunov_solve_factored", bm_lyapunov_solve_factored},
      {"alt_lyapunov_dgees_dtrsyl", bm_alt_lyapunov_dgees_dtrsyl},
  };
  // The n² Kronecker operator is 1296×1296 at n = 36: its setup alone would dominate a run.
  const std::pair<const char*, Function> up_to_18[] = {
      {"alt_lyapunov_kronecker_inverse", bm_alt_kronecker_inverse},
      {"alt_lyapunov_packed_lu", bm_alt_packed_lu},
      {"alt_lyapunov_schur_precomputed", bm_alt_schur_precomputed},
  };
  const std::pair<const char*, Function> direct[] = {
      {"solve_care", bm_solve_care<thetad::CareMethod::automatic>},
      {"care_solver", bm_care_solver},
      {"sb02md", bm_sb02md},
  };
  for (const Problem& p : unit_weight_problems)
    for (const auto& [name, function] : direct)
      benchmark::RegisterBenchmark((std::string(name) + "/" + p.name).c_str(), function, p)
          ->Unit(benchmark::kMicrosecond);
  for (const Problem& p : problems) {
    for (const auto& [name, function] : every_size)
      benchmark::RegisterBenchmark((std::string(name) + "/" + p.name).c_str(), function, p)
          ->Unit(benchmark::kMicrosecond);
    if (p.lyapunov)
      benchmark::RegisterBenchmark(("constant_lyapunov_solve/" + p.name).c_str(), bm_constant_lyapunov, p)
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
