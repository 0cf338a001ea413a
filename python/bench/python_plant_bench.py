"""What a plant written in Python costs (docs/python.md, "A plant written in Python"): the RTAC/TORA of
python/tests/tora.py against the shipped C++ "tora", flown from the same state by the same controller,
interleaved: plant steps (RK4, 1 ms; the controller every step) per second of the process's CPU time, best
and median of the repetitions.

CPU time, because the host is shared: wall time counts what other processes took.

Usage (from the build folder): PYTHONPATH=. /usr/bin/python3 ../python/bench/python_plant_bench.py
[--repetitions N] [--duration S] [--controllers lqr,theta-d]. Pin it (taskset -c 1) for steadier figures.
"""

import argparse
import os
import sys
import time

import numpy as np

import thetad

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from tora import PythonTora  # noqa: E402


def steps_per_second(plant, controller, duration):
    cpu = time.process_time()
    result = thetad.run(plant=plant, controller=controller, duration_s=duration, summary_only=True, timing=False)
    cpu = time.process_time() - cpu
    if not result.completed:
        raise RuntimeError(f"{controller} on {plant}: {result.status_text}: {result.reason}")
    return result.summary["controller_samples"] / cpu


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repetitions", type=int, default=5)
    parser.add_argument("--duration", type=float, default=20.0, help="seconds flown from x0 = [1, 0, 0, 0]")
    parser.add_argument("--controllers", default="lqr,theta-d")
    arguments = parser.parse_args()

    print(f"tora, {arguments.duration:g} s at 1 kHz: steps per CPU second, best and median of "
          f"{arguments.repetitions} interleaved flights")
    print(f"  {'controller':10s} {'plant':10s} {'best':>10s} {'median':>10s}")
    for controller in arguments.controllers.split(","):
        rates = {"C++": [], "Python": []}
        for _ in range(arguments.repetitions):
            rates["C++"].append(steps_per_second("tora", controller, arguments.duration))
            rates["Python"].append(steps_per_second(PythonTora(), controller, arguments.duration))
        for plant, values in rates.items():
            print(f"  {controller:10s} {plant:10s} {max(values):10.0f} {np.median(values):10.0f}")


if __name__ == "__main__":
    main()
