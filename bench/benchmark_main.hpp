#pragma once

// main() of a benchmark program that registers its rows at run time: after static initialization,
// when every controller has registered itself, so that the rows can follow the registry.

#include <benchmark/benchmark.h>

namespace thetad::bench {

inline int run_benchmarks(int argc, char** argv, void (*register_benchmarks)()) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_benchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace thetad::bench
