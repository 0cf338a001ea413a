"""The simulator releases the GIL while it flies a C++ controller, whatever the host's load."""

import threading
import time

import thetad


def test_python_runs_while_a_flight_flies():
    # Whatever the host's load: with the GIL held by the flight, this thread could not count at
    # all until the flight ended. The flight lasts long enough (30 s simulated, ~0.7 s on an idle
    # core) for 1000 counts with the GIL free.
    flight_done = threading.Event()
    counted_while_flying = 0

    def long_flight():
        thetad.run("scenario-1", "theta-d", duration_s=30.0, summary_only=True, timing=False)
        flight_done.set()

    flying = threading.Thread(target=long_flight)
    flying.start()
    time.sleep(0.05)
    while not flight_done.is_set() and counted_while_flying < 1000:
        counted_while_flying += 1
        time.sleep(0)
    flying.join()
    assert counted_while_flying == 1000
