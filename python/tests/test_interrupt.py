"""A flight from Python stops at Ctrl-C and reports its progress. The flight runs with the GIL
released; its observer (python/task_observer.cpp) takes the GIL every 50 ms of wall time to check
for signals and calls the progress callback at most 10 times a second."""

import time

import pytest

import thetad
from interrupted import interrupt

# A flight far longer than the test: only Ctrl-C ends it. It would write its result into `folder`
# once flown; interrupted, nothing may be there. With "python", the controller is a Python class
# (around theta-d), whose own code then usually receives the Ctrl-C.
SETUP = """
    class Wrapped(thetad.Controller):
        def __init__(self):
            super().__init__()
            self.inner = thetad.controller("theta-d")

        def reset(self, x0, t0):
            self.inner.reset(x0, t0)

        def compute(self, t, x, reference):
            return self.inner.compute(t, x, reference)

    folder, kind = sys.argv[1:]
    controller = Wrapped() if kind == "python" else "theta-d"
    thetad.run("scenario-1", controller, duration_s=0.1, summary_only=True, timing=False)  # warm
"""
FLIGHT = 'thetad.run("scenario-1", controller, duration_s=3600.0, summary_only=True, timing=False).write(folder)'


@pytest.mark.parametrize("kind", ["c++", "python"])
def test_ctrl_c_stops_a_flight_within_a_second(tmp_path, kind):
    folder = tmp_path / "out"
    folder.mkdir()
    message = interrupt(SETUP, FLIGHT, folder, kind)
    assert "stopped at t = " in message and "no result" in message
    assert list(folder.iterdir()) == []


def test_progress_is_called_with_increasing_times_at_most_ten_times_a_second():
    calls = []
    result = thetad.run("scenario-1", "theta-d", duration_s=30.0, summary_only=True, timing=False,
                        progress=lambda t, duration: calls.append((time.monotonic(), t, duration)))
    assert len(calls) >= 2
    times = [t for _, t, _ in calls]
    assert times == sorted(times) and len(set(times)) == len(times)
    assert all(duration == 30.0 for _, _, duration in calls)
    assert calls[-1][1] == result.summary["end_time_s"] == 30.0
    gaps = [b[0] - a[0] for a, b in zip(calls[:-2], calls[1:-1])]  # the final call comes when the flight ends
    assert all(gap >= 0.09 for gap in gaps), gaps


def test_an_exception_in_progress_stops_the_flight():
    def progress(t, duration):
        raise RuntimeError(f"stop at {t}")

    started = time.monotonic()
    with pytest.raises(RuntimeError, match="stop at"):
        thetad.run("scenario-1", "theta-d", duration_s=3600.0, summary_only=True, timing=False, progress=progress)
    assert time.monotonic() - started < 10.0
    with pytest.raises(TypeError, match=r"progress: expected None, True \(a bar\) or a callable"):
        thetad.run("scenario-1", "theta-d", duration_s=0.1, progress=3)


def test_compare_reports_each_flight_to_its_end():
    ends = []
    thetad.compare("scenario-1", ["theta-d", "sdre"], duration_s=1.0, summary_only=True, timing=False,
                   progress=lambda t, duration: ends.append((t, duration)))
    assert ends.count((1.0, 1.0)) == 2
