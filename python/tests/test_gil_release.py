"""The simulator releases the GIL while it flies a C++ controller: another Python thread runs
during the flight. Checked by order of events, not by a wall-time bound, so a busy host cannot
fail it: the main thread records when it runs, the flight thread when the flight starts and ends,
and some main-thread step must fall in the middle third of the flight. A flight holding the GIL
would let the main thread run only around its ends, within the interpreter's switch interval
(5 ms) of them; the flight lasts far longer. The speed-up this gives is measured by
python/bench/thread_speedup.py."""

import threading
import time

import thetad


def test_another_python_thread_runs_while_a_flight_flies():
    thetad.run("scenario-1", "theta-d", duration_s=0.1, summary_only=True, timing=False)  # warm
    window = {}
    started = threading.Event()

    def flight():
        started.set()
        window["start"] = time.perf_counter()
        thetad.run("scenario-1", "theta-d", duration_s=10.0, summary_only=True, timing=False)
        window["end"] = time.perf_counter()

    thread = threading.Thread(target=flight)
    thread.start()
    started.wait()
    steps = []
    while thread.is_alive():
        steps.append(time.perf_counter())
    thread.join()
    start, end = window["start"], window["end"]
    assert end - start > 0.05, f"the flight took {end - start:.3f} s: too short to tell"
    third = (end - start) / 3
    inside = [t for t in steps if start + third < t < end - third]
    assert inside, (f"no step of the main thread in the middle third of a {end - start:.3f} s flight "
                    f"({len(steps)} steps in all): the flight held the GIL")
