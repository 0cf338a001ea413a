// How the per-step cost of the controllers grows with the state dimension, on synthetic SDC plants
// of n = 6, 12, 18, 24, 36, 48, 60, 72 states and m = n/3 inputs (thetad::RandomSdcPlant:
// F(x) = A + x1 C + x2² D, B(x) = G + x1 E with dense random C, D, E, so every row is nonlinear
// and every coefficient of F and B varies; (F, B) is stabilizable with probability one at every
// state).
// bench/report.py fits the log-log slope of the medians against n.
//
// The rows: every registered controller that flies a plant other than the helicopter, built by
// name with its defaults (the plant's design defaults: Q = I, R = I, u0 = 0) and named by its
// Controller::name() (theta-d with 3 terms; sdre-warm), plus the variants below; those that need
// the helicopter refuse the synthetic plant and are left out (said on stderr). And, built
// directly, the floor of any controller: one fixed gain (LqrController at the origin, "lqr").
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
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "bench/benchmark_main.hpp"
#include "controllers/lqr.hpp"
#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "tests/test_plants.hpp"

namespace {

constexpr int kStates = 1000;

// Settings timed besides a registered controller's defaults: the SDRE's cold mode (solve_care at
// every pass) beside its warm default (Newton–Kleinman from the last P).
const std::multimap<std::string, std::string> kVariants = {{"sdre", "mode: cold"}};

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

// Builds one row's controller for a plant.
using Make = std::function<std::unique_ptr<thetad::Controller>(const thetad::SdcPlant& plant)>;

Make registered(const std::string& name, const std::string& settings) {
  return [name, settings](const thetad::SdcPlant& plant) {
    const thetad::ControllerContext at_rest{plant, Eigen::VectorXd::Zero(plant.state_dim())};
    return thetad::ControllerRegistry::instance().make(name, YAML::Load(settings), at_rest);
  };
}

std::unique_ptr<thetad::Controller> fixed_gain(const thetad::SdcPlant& plant) {
  const Eigen::Index n = plant.state_dim(), m = plant.input_dim();
  const thetad::OperatingPoint origin{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(m), Eigen::VectorXd::Zero(n)};
  return std::make_unique<thetad::LqrController>(
      plant, origin, thetad::LqrSettings{Eigen::MatrixXd::Identity(n, n), Eigen::MatrixXd::Identity(m, m), 0});
}

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

  Fixture(const Make& make, int n, int m)
      : plant(n, m, 1000 + static_cast<std::uint64_t>(n)), path(smooth_path(n)), controller(make(plant)), u(m) {
    controller->reset(Eigen::VectorXd::Zero(n), 0.0);
    step();  // untimed: the SDRE's first solve is cold
  }

  void step() {
    t += 1e-3;
    controller->control(t, path.states[k], thetad::Reference{}, u);
    if (++k == path.states.size()) k = 0;
  }
};

void control_step(benchmark::State& state, const std::string& row, const Make& make) {
  const int n = static_cast<int>(state.range(0)), m = std::max(1, n / 3);
  static std::map<std::pair<std::string, int>, std::unique_ptr<Fixture>> fixtures;
  auto& fixture = fixtures[{row, n}];
  if (!fixture) fixture = std::make_unique<Fixture>(make, n, m);
  for (auto _ : state) {
    fixture->step();
    benchmark::DoNotOptimize(fixture->u.data());
    benchmark::ClobberMemory();
  }
  state.counters["n"] = n;
  state.counters["m"] = m;
}

void register_benchmarks() {
  std::vector<std::pair<std::string, Make>> rows;
  const thetad::RandomSdcPlant probe(6, 2, 1);
  for (const std::string& name : thetad::ControllerRegistry::instance().names()) {
    std::vector<std::string> settings{"{}"};
    for (auto [it, end] = kVariants.equal_range(name); it != end; ++it) settings.push_back(it->second);
    for (const std::string& block : settings) {
      const Make make = registered(name, block);
      try {
        rows.emplace_back(make(probe)->name(), make);
      } catch (const thetad::Error& error) {
        std::fprintf(stderr, "scaling_bench: left out: %s\n", error.what());
        break;
      }
    }
  }
  rows.emplace_back("lqr", fixed_gain);
  for (const auto& [row, make] : rows) {
    auto* benchmark = benchmark::RegisterBenchmark(("control_step/" + row).c_str(), control_step, row, make);
    for (const int n : {6, 12, 18, 24, 36, 48, 60, 72}) benchmark->Arg(n);
    benchmark->ArgName("n")->Unit(benchmark::kMicrosecond);
  }
}

}  // namespace

int main(int argc, char** argv) { return thetad::bench::run_benchmarks(argc, argv, register_benchmarks); }
