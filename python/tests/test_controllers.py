"""Registered controllers by name and settings, and controllers written in Python flying in the
C++ simulator."""

import math

import numpy as np
import pytest

import thetad
from hover import recover_hover
from pd_controller import HoverPD


def test_every_registered_controller_is_listed():
    listed = {entry["name"]: entry for entry in thetad.controllers()}
    assert {"theta-d", "sdre", "lqr", "lqr-scheduled", "example-pid"} <= set(listed)
    assert listed["theta-d"]["origin"] == "built-in" and listed["sdre"]["description"]


def test_a_controller_by_name_with_settings_as_keywords(hover_trim):
    tuned = thetad.controller("theta-d", label="tuned", terms=3, k=[0.5, 2.0], l=[0.1, 0.2])
    assert isinstance(tuned, thetad.Controller)
    assert (tuned.label, tuned.controller) == ("tuned", "theta-d")
    settings = tuned.settings
    assert settings["k"] == [0.5, 2.0] and settings["l"] == [0.1, 0.2] and len(settings["Q"]) == 18
    u = tuned.compute(0.0, hover_trim.state, thetad.Reference(hover_trim.state[:3]))
    assert u.shape == (5,) and np.all(np.isfinite(u))
    default = thetad.controller("theta-d")
    assert not np.array_equal(u, default.compute(0.0, hover_trim.state, hover_trim.state[:3]))


def test_lqr_holds_the_trim_it_was_designed_at(hover_trim):
    lqr = thetad.controller("lqr")
    u = lqr.compute(0.0, hover_trim.state, thetad.Reference(hover_trim.state[:3], np.zeros(3)))
    np.testing.assert_allclose(u, hover_trim.input, rtol=1e-9, atol=1e-12)


def test_settings_errors_name_the_field():
    with pytest.raises(thetad.Error, match="field 'kk'"):
        thetad.controller("theta-d", kk=[1.0])
    with pytest.raises(thetad.Error, match="field 'k': expected 2 entries"):
        thetad.controller("theta-d", k=[1.0])
    with pytest.raises(thetad.Error, match="unknown controller 'theta'.*theta-d"):
        thetad.controller("theta")
    with pytest.raises(TypeError, match="theta-d.k"):
        thetad.controller("theta-d", k=[object()])


def test_compute_checks_its_arguments(hover_trim):
    lqr = thetad.controller("lqr")
    with pytest.raises(ValueError, match=r"compute: x: expected shape \(18,\), got \(14,\)"):
        lqr.compute(0.0, np.zeros(14), hover_trim.state[:3])
    with pytest.raises(ValueError, match=r"expected shape \(3,\), got \(2,\)"):
        lqr.compute(0.0, hover_trim.state, [0.0, 1.0])


def test_clone_is_independent(hover_trim):
    sdre = thetad.controller("sdre")
    copy = sdre.clone()
    assert copy.settings == sdre.settings and copy is not sdre
    reference = thetad.Reference(hover_trim.state[:3])
    np.testing.assert_array_equal(copy.compute(0.0, hover_trim.state, reference),
                                  sdre.compute(0.0, hover_trim.state, reference))


# The tolerance of the C++ example PID's test (tests/controllers/pid_example_test.cpp): from 1 m in
# x, y or z, within 0.1 m of the hover point in under 3 s and after 8 s.
@pytest.mark.parametrize("offset", [(1, 0, 0), (0, 1, 0), (0, 0, 1)])
def test_a_python_pd_controller_returns_to_hover(tmp_path, hover_trim, offset):
    result, settling_time, final_error = recover_hover(tmp_path, hover_trim, HoverPD(hover_trim), offset, 8.0, 0.1)
    assert result.completed, result.reason
    assert (result.label, result.controller) == ("HoverPD", "python:HoverPD")
    assert result.controller_origin.startswith("python class ") and result.controller_origin.endswith("HoverPD")
    assert settling_time < 3.0
    assert final_error < 0.1


class Raises(thetad.Controller):
    def __init__(self, after):
        super().__init__()
        self.after = after

    def compute(self, t, x, reference):
        if t >= self.after:
            raise ZeroDivisionError("the controller gave up")
        return [80.0, 0.0, 0.0, 0.0, 0.0]


class Returns(thetad.Controller):
    def __init__(self, u):
        super().__init__()
        self.u = u

    def name(self):
        return "returns"

    def compute(self, t, x, reference):
        return self.u


def test_a_python_exception_ends_the_run_as_failed():
    result = thetad.run("hover-step", Raises(after=0.05), label="raiser", duration_s=0.2, summary_only=True)
    assert not result.completed and result.label == "raiser"
    assert result.status == "failed" and result.status_text.startswith("failed at 0.05")
    assert "Raises.compute raised ZeroDivisionError: the controller gave up" in result.reason
    assert result.summary["end_time_s"] == pytest.approx(0.05, abs=1e-3)


@pytest.mark.parametrize(
    "u, reason",
    [
        ([math.nan, 0.0, 0.0, 0.0, 0.0], "non-finite command"),
        ([80.0, 0.0, 0.0], r"returned u: expected shape (5,), got (3,)"),
        ("thrust", "returned u: expected a real vector"),
    ],
)
def test_a_bad_python_result_ends_the_run_as_failed(u, reason):
    result = thetad.run("hover-step", Returns(u), duration_s=0.1, summary_only=True)
    assert not result.completed and result.label == "returns" and result.status == "failed"
    assert reason in result.reason


class Counter(thetad.Controller):
    def __init__(self):
        super().__init__()
        self.calls = 0

    def compute(self, t, x, reference):
        self.calls += 1
        return [80.0, 0.0, 0.0, 0.0, 0.0]


class CopyableCounter(Counter):
    def clone(self):
        return CopyableCounter()


def test_clone_of_a_python_controller(hover_trim):
    x, position = hover_trim.state, hover_trim.state[:3]
    # Without a clone() of its own: a second handle on the same object, which it keeps alive.
    original = Counter()
    handle = original.clone()
    assert isinstance(handle, thetad.Controller) and handle.name() == "Counter"
    handle.compute(0.0, x, position)  # through C++ into the original's compute
    assert original.calls == 1
    orphan = Counter().clone()  # the only reference to its Counter is the handle's
    orphan.compute(0.0, x, position)
    # A clone flies as its original does.
    result = thetad.run("hover-step", handle, label="handle", duration_s=0.01, summary_only=True)
    assert result.completed and original.calls == 1 + 10
    # With one: the C++ clone() calls it and the copy is independent.
    copyable = CopyableCounter()
    copy = thetad.Controller.clone(copyable)
    copy.compute(0.0, x, position)
    assert copyable.calls == 0


def test_a_controller_without_compute_fails_its_run():
    result = thetad.run("hover-step", thetad.Controller(), label="bare", duration_s=0.1, summary_only=True)
    assert not result.completed and "does not define compute" in result.reason


def test_reset_is_called_with_the_initial_state():
    class Recorder(Returns):
        def reset(self, x0, t0):
            self.x0, self.t0 = x0, t0

    recorder = Recorder([80.0, 0.0, 0.0, 0.0, 0.0])
    thetad.run("hover-step", recorder, duration_s=0.01, summary_only=True)
    assert recorder.x0.shape == (18,) and recorder.t0 == 0.0 and recorder.x0[17] == 1.0


def test_python_and_registered_controllers_compare_on_one_flight(hover_trim):
    results = thetad.compare("hover-step", ["lqr", thetad.controller("theta-d", label="td"), HoverPD(hover_trim)],
                             duration_s=0.5, seed=3, summary_only=True)
    assert [r.label for r in results] == ["lqr", "td", "HoverPD"]
    assert {r.provenance["seed"] for r in results} == {3}
    table = thetad.comparison_table(results)
    assert all(label in table for label in ("lqr", "td", "HoverPD"))
    with pytest.raises(thetad.Error, match="label"):
        thetad.compare("hover-step", ["lqr", "lqr"], duration_s=0.1)
