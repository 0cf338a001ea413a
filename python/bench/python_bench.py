"""What crossing into Python costs (docs/performance.md, "Python"):

1. A Python call of a C++ controller's compute(t, x, reference): microseconds of CPU time per
   call, best of repetitions; the C++ call itself is controllers_bench's row of the same
   controller (Google Benchmark's CPU time).
2. A controller written in Python (python/tests/pd_controller.py) flying scenario I: the real-time
   factor on one core (simulated seconds per second of the process's CPU time; the wall-clock
   factor beside it), interleaved with the C++ LQR on the same flight, whose factor is the
   simulator's own ceiling.

CPU time, because the host is shared: wall time counts what other processes took.

Usage (from the build folder): PYTHONPATH=. /usr/bin/python3 ../python/bench/python_bench.py
[--repetitions N] [--duration S]. Pin it (taskset -c 1) for steadier figures.
"""

import argparse
import os
import sys
import time
import timeit

import numpy as np

import thetad

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from pd_controller import HoverPD  # noqa: E402


def call_cost(controller, repetitions, calls=20000):
    """Seconds per compute() call from Python, best of `repetitions`, on the hover trim state."""
    trim = thetad.Helicopter().trim(altitude=3.5)
    x, reference = trim.state.copy(), thetad.Reference(trim.state[:3])
    times = timeit.repeat(lambda: controller.compute(0.0, x, reference), number=calls, repeat=repetitions,
                          timer=time.process_time)
    return min(times) / calls


def real_time_factors(controller, duration):
    """(per CPU second, per wall second) of one flight."""
    start, cpu = time.perf_counter(), time.process_time()
    result = thetad.run("scenario-1", controller, seed=1, duration=duration, summary_only=True, timing=False)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    if not result.completed:
        raise RuntimeError(f"{result.label}: {result.status}")
    return duration / cpu, duration / wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repetitions", type=int, default=7)
    parser.add_argument("--duration", type=float, default=85.0, help="seconds of scenario I flown (85: all of it)")
    arguments = parser.parse_args()

    print("compute() called from Python (µs of CPU time per call, best of %d x 20000 calls):" % arguments.repetitions)
    for name in ("lqr", "lqr-scheduled", "theta-d"):
        controller = thetad.controller(name)
        print(f"  {name:14s} {call_cost(controller, arguments.repetitions) * 1e6:8.3f}")

    trim = thetad.Helicopter().trim(altitude=3.5)
    factors = {"python-pd": [], "lqr (C++)": []}
    for _ in range(max(1, arguments.repetitions // 2)):
        factors["python-pd"].append(real_time_factors(HoverPD(trim), arguments.duration))
        factors["lqr (C++)"].append(real_time_factors("lqr", arguments.duration))
    print(f"scenario I, {arguments.duration:g} s, seed 1, all disturbances: real-time factor over "
          f"{len(factors['lqr (C++)'])} interleaved flights")
    print(f"  {'':14s} {'one core: best':>15s} {'median':>8s} {'wall: best':>11s} {'median':>8s}")
    for label, values in factors.items():
        cpu, wall = np.array(values).T
        print(f"  {label:14s} {cpu.max():15.1f} {np.median(cpu):8.1f} {wall.max():11.1f} {np.median(wall):8.1f}")


if __name__ == "__main__":
    main()
