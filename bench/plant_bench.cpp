// The helicopter plant's hot path: one right-hand side, the SDC matrices, one RK4 step, and the
// rotor-speed zero-finding (docs/model.md §4.2). Fixed-size buffers, preallocated outside the loops.
#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include "core/helicopter/helicopter.hpp"
#include "core/helicopter/rotor_speed.hpp"

namespace {

using namespace thetad::heli;
using Vector18 = Eigen::Matrix<double, kStateDim, 1>;
using Vector5 = Eigen::Matrix<double, kInputDim, 1>;

// A state in slow forward flight with some attitude, rates and flapping, and an input near hover.
Vector18 flight_state() {
  Vector18 x = Vector18::Zero();
  x[kZp] = -3.5;
  x[kU] = 1.5;
  x[kV] = -0.4;
  x[kW] = 0.2;
  x[kPhi] = 0.08;
  x[kTheta] = -0.03;
  x[kPsi] = 0.2;
  x[kP] = 0.1;
  x[kQ] = -0.05;
  x[kR] = 0.02;
  x[kA1] = 0.004;
  x[kB1] = 0.008;
  x[kS] = 1.0;
  return x;
}

Vector5 hover_input() {
  Vector5 u;
  u << 80.5, -0.168, 0.0, 0.001, 0.0018;
  return u;
}

Helicopter windy_helicopter() {
  Helicopter heli;
  Environment env;
  env.wind_ned = Eigen::Vector3d(1.77, 0.2, 0.0);
  heli.set_environment(env);
  return heli;
}

void BM_PlantF(benchmark::State& state) {
  const Helicopter heli = windy_helicopter();
  const Vector18 x = flight_state();
  const Vector5 u = hover_input();
  Vector18 xdot;
  for (auto _ : state) {
    heli.f(x, u, xdot);
    benchmark::DoNotOptimize(xdot.data());
  }
}
BENCHMARK(BM_PlantF);

void BM_PlantSdc(benchmark::State& state) {
  const Helicopter heli = windy_helicopter();
  const Vector18 x = flight_state();
  const Vector5 u = hover_input();
  Eigen::Matrix<double, kStateDim, kStateDim> F;
  Eigen::Matrix<double, kStateDim, kInputDim> B;
  for (auto _ : state) {
    heli.sdc(x, u, F, B);
    benchmark::DoNotOptimize(F.data());
    benchmark::DoNotOptimize(B.data());
  }
}
BENCHMARK(BM_PlantSdc);

void BM_PlantSdcAtRotorSpeed(benchmark::State& state) {
  const Helicopter heli = windy_helicopter();
  const Vector18 x = flight_state();
  Eigen::Matrix<double, kStateDim, kStateDim> F;
  Eigen::Matrix<double, kStateDim, kInputDim> B;
  for (auto _ : state) {
    heli.sdc_at_rotor_speed(x, 171.9, F, B);
    benchmark::DoNotOptimize(F.data());
    benchmark::DoNotOptimize(B.data());
  }
}
BENCHMARK(BM_PlantSdcAtRotorSpeed);

// One classical RK4 step of 1 ms with the input held (what the simulator does per sample).
void BM_PlantRk4Step(benchmark::State& state) {
  const Helicopter heli = windy_helicopter();
  const Vector18 x0 = flight_state();
  const Vector5 u = hover_input();
  const double dt = 1e-3;
  Vector18 x = x0, k1, k2, k3, k4, stage;
  for (auto _ : state) {
    heli.f(x, u, k1);
    stage = x + 0.5 * dt * k1;
    heli.f(stage, u, k2);
    stage = x + 0.5 * dt * k2;
    heli.f(stage, u, k3);
    stage = x + dt * k3;
    heli.f(stage, u, k4);
    x += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    benchmark::DoNotOptimize(x.data());
    x = x0;  // every iteration steps from the same state
  }
}
BENCHMARK(BM_PlantRk4Step);

void BM_MainRotorSpeed(benchmark::State& state) {
  const Parameters p = Parameters::nominal();
  double thrust = 80.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(main_rotor_speed(p, thrust, 1.6, 0.3, p.omega_nom));
    thrust = thrust < 120.0 ? thrust + 0.01 : 80.0;  // vary the root so nothing is cached
  }
}
BENCHMARK(BM_MainRotorSpeed);

}  // namespace

BENCHMARK_MAIN();
