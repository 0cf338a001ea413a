"""The simulator releases the GIL while it flies a C++ controller, so flights in a thread pool run in
parallel: how much faster 8 flights go on 2 threads than one by one. A ratio of wall times in one
process, sequential and pooled runs interleaved, best of a few repetitions (the best of each is the
least disturbed), with the cores the pooled runs got beside it. A benchmark, not a test: on a
shared host the ratio follows the load (1.90-1.99x on a quiet 2-vCPU VM, under 1.5x with a core
partly taken). python/tests/test_gil_release.py checks the release itself, without a clock bound.

Usage (from the build folder): PYTHONPATH=. /usr/bin/python3 ../python/bench/thread_speedup.py
[--repetitions N]
"""

import argparse
import time
from concurrent.futures import ThreadPoolExecutor

import thetad

FLIGHTS = 8
WORKERS = 2


def fly(seed):
    # θ–D: its design needs no trim (Ipopt solves are serialized), so its flights are all C++ in
    # parallel. 4 s of flight (~0.06 s of CPU) keeps what a call does holding the GIL (its
    # arguments, its result, the pool's hand-offs) small beside it.
    return thetad.run("scenario-1", "theta-d", seed=seed, duration=4.0, summary_only=True, timing=False)


def sequential():
    return [fly(seed) for seed in range(FLIGHTS)]


def pooled():
    with ThreadPoolExecutor(max_workers=WORKERS) as pool:
        return list(pool.map(fly, range(FLIGHTS)))


def timed(run):
    """Wall seconds, the process's CPU seconds per wall second (how many cores it got), results."""
    start, cpu = time.perf_counter(), time.process_time()
    results = run()
    wall = time.perf_counter() - start
    return wall, (time.process_time() - cpu) / wall, results


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repetitions", type=int, default=5)
    arguments = parser.parse_args()
    fly(0)  # warm: the scenario file and the shared libraries
    one_by_one, in_pool, cores = [], [], []
    for _ in range(arguments.repetitions):
        seconds, _, reference = timed(sequential)
        one_by_one.append(seconds)
        seconds, used, results = timed(pooled)
        in_pool.append(seconds)
        cores.append(used)
        if [r.summary["cost"] for r in results] != [r.summary["cost"] for r in reference]:
            raise SystemExit("the pooled flights differ from the sequential ones")
    print(f"{FLIGHTS} flights: one by one {min(one_by_one):.3f} s, {WORKERS} threads {min(in_pool):.3f} s "
          f"({min(one_by_one) / min(in_pool):.2f}x); the pooled runs got {max(cores):.2f} cores at best")


if __name__ == "__main__":
    main()
