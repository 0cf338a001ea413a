// How the per-step cost of θ–D, SDRE (cold, warm) and LQR grows with the state dimension, on
// synthetic SDC plants of n = 6, 12, 18, 36, 72 states and m = n/3 inputs (thetad::RandomSdcPlant:
// F(x) = A + x1 C + x2² D, B(x) = G + x1 E with dense random C, D, E, so every row is nonlinear and
// every coefficient of F and B varies; (F, B) is stabilizable with probability one at every state).
// bench/report.py fits the log-log slope of the medians against n.
//
// The states: a smooth periodic path x_k(j) = 0.2 sin(2π f_j k / K + φ_j), f_j ∈ {1, 2, 3},
// K = 1000, so that the SDRE's warm start sees small step-to-step changes and the cycle closes
// without a jump.
//
// Set-up costs, paid once per row outside the timing: θ–D's ConstantLyapunovSolver is O(n⁶) to
// build (its packed operator is n(n+1)/2 square: 2628² = 55 MB at n = 72, seconds to invert).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "controllers/lqr.hpp"
#include "controllers/sdre.hpp"
#include "controllers/theta_d.hpp"
#include "tests/test_plants.hpp"

namespace {

constexpr int kStates = 1000;

struct Path {
  std::vector<Eigen::VectorXd> states;
};

Path smooth_path(int n) {
  std::mt19937_64 generator(static_cast<std::uint64_t>(n));
  std::uniform_int_distribution<int> frequency(1, 3);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
  Eigen::VectorXd f(n), phi(n);
  for (int j = 0; j < n; ++j) {
    f[j] = frequency(generator);
    phi[j] = phase(generator);
  }
  Path path;
  for (int k = 0; k < kStates; ++k)
    path.states.push_back(0.2 * (2.0 * std::numbers::pi * k / kStates * f + phi).array().sin().matrix());
  return path;
}

enum class Kind { theta_d, sdre_cold, sdre_warm, lqr };

// A plant, its path and one controller, reset once: θ–D's reset builds the O(n⁶) Lyapunov
// operator, and Google Benchmark calls a benchmark function several times (iteration estimate,
// repetitions). Later calls continue where the last one stopped on the path and in time.
struct Fixture {
  thetad::RandomSdcPlant plant;
  Path path;
  std::unique_ptr<thetad::Controller> controller;
  Eigen::VectorXd u;
  std::size_t k = 0;
  double t = 0.0;

  Fixture(Kind kind, int n, int m) : plant(n, m, 1000 + static_cast<std::uint64_t>(n)), path(smooth_path(n)), u(m) {
    const Eigen::MatrixXd Q = Eigen::MatrixXd::Identity(n, n), R = Eigen::MatrixXd::Identity(m, m);
    switch (kind) {
      case Kind::theta_d: {
        thetad::ThetaDSettings s;
        s.terms = 3;  // the paper's T0 + T1 + T2; this plant's SDC does not depend on u: one pass
        s.Q = Q;
        s.R = R;
        controller = std::make_unique<thetad::ThetaDController>(plant, s);
        break;
      }
      case Kind::sdre_cold:
      case Kind::sdre_warm: {
        thetad::SdreSettings s;
        s.mode = kind == Kind::sdre_cold ? thetad::SdreSettings::Mode::cold : thetad::SdreSettings::Mode::warm;
        s.Q = Q;
        s.R = R;
        controller = std::make_unique<thetad::SdreController>(plant, s);
        break;
      }
      case Kind::lqr: {
        const thetad::OperatingPoint origin{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(m),
                                            Eigen::VectorXd::Zero(n)};
        controller = std::make_unique<thetad::LqrController>(plant, origin, thetad::LqrSettings{Q, R, 0});
        break;
      }
    }
    controller->reset(Eigen::VectorXd::Zero(n), 0.0);
    step();  // untimed: the SDRE's first solve is cold
  }

  void step() {
    t += 1e-3;
    controller->control(t, path.states[k], thetad::Reference{}, u);
    if (++k == path.states.size()) k = 0;
  }
};

void control_step(benchmark::State& state, Kind kind) {
  const int n = static_cast<int>(state.range(0)), m = std::max(1, n / 3);
  static std::map<std::pair<Kind, int>, std::unique_ptr<Fixture>> fixtures;
  auto& fixture = fixtures[{kind, n}];
  if (!fixture) fixture = std::make_unique<Fixture>(kind, n, m);
  for (auto _ : state) {
    fixture->step();
    benchmark::DoNotOptimize(fixture->u.data());
    benchmark::ClobberMemory();
  }
  state.counters["n"] = n;
  state.counters["m"] = m;
}

void dimensions(benchmark::internal::Benchmark* b) {
  for (const int n : {6, 12, 18, 36, 72}) b->Arg(n);
  b->ArgName("n")->Unit(benchmark::kMicrosecond);
}

BENCHMARK_CAPTURE(control_step, theta_d, Kind::theta_d)->Apply(dimensions);
BENCHMARK_CAPTURE(control_step, sdre_cold, Kind::sdre_cold)->Apply(dimensions);
BENCHMARK_CAPTURE(control_step, sdre_warm, Kind::sdre_warm)->Apply(dimensions);
BENCHMARK_CAPTURE(control_step, lqr, Kind::lqr)->Apply(dimensions);

}  // namespace

BENCHMARK_MAIN();
