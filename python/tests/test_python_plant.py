"""A plant written in Python (docs/python.md, "A plant written in Python"): flown by θ–D and the SDRE through
run, compare and optimal; the same results as the same plant in C++; what its methods raise or return wrong
ends the run with a reason that names the class and the method; the SDC identity checked on request."""

import math
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import thetad
from tora import PythonTora


class Pendulum(thetad.Plant):
    """An inverted pendulum, θ from upright: θ'' = (g/l) sin θ − b θ' + u / I; F holds (g/l) sin θ / θ."""

    state_dim, input_dim = 2, 1
    state_names = [("theta", "rad"), ("omega", "rad_per_s")]
    input_names = [("torque", "N_m")]

    def __init__(self, gravity_over_length=9.81, damping=0.1, inertia=1.0):
        self.a, self.b, self.inertia = gravity_over_length, damping, inertia

    def f(self, x, u):
        return np.array([x[1], self.a * math.sin(x[0]) - self.b * x[1] + u[0] / self.inertia])

    def sdc(self, x, u):
        sinc = math.sin(x[0]) / x[0] if x[0] != 0.0 else 1.0
        return np.array([[0.0, 1.0], [self.a * sinc, -self.b]]), np.array([[0.0], [1.0 / self.inertia]])

    def design_defaults(self):
        return [10.0, 1.0], None, None


FLIGHT = dict(initial_state=[0.5, 0.0], duration_s=2, timing=False)


def test_theta_d_and_the_sdre_bring_a_python_pendulum_upright():
    runs = thetad.compare(controllers=["theta-d", "sdre"], plant=Pendulum(), **FLIGHT)
    for run in runs:
        assert run.completed, run.reason
        assert run.provenance["plant"] == "python:Pendulum"
        assert run.provenance["initial_state"] == [0.5, 0.0]
        assert run.columns[:3] == ["t_s", "theta_rad", "omega_rad_per_s"] and "cmd_torque_N_m" in run.columns
        assert abs(run.log[-1, 1]) < 0.01
        assert run.settings["Q"] == [10.0, 1.0]  # the plant's design defaults, as used


@pytest.mark.parametrize("controller", ["theta-d", "sdre", "lqr"])
def test_the_tora_in_python_flies_as_the_shipped_one(controller):
    python = thetad.run(plant=PythonTora(), controller=controller, duration_s=1, timing=False)
    shipped = thetad.run(plant="tora", controller=controller, duration_s=1, timing=False)
    assert python.completed and python.provenance["plant"] == "python:PythonTora"
    assert python.columns == shipped.columns
    # Bit for bit: the same operations in the same order, the same libm.
    np.testing.assert_array_equal(python.log, shipped.log)
    assert python.summary["cost"] == shipped.summary["cost"]


class StiffTorque(Pendulum):
    """The torque through a stiffening gain, u (1 + u²/100): B depends on u."""

    sdc_depends_on_input = True

    def f(self, x, u):
        return np.array([x[1], self.a * math.sin(x[0]) - self.b * x[1] + u[0] * (1.0 + u[0] ** 2 / 100.0)])

    def sdc(self, x, u):
        F, _ = super().sdc(x, u)
        return F, np.array([[0.0], [1.0 + u[0] ** 2 / 100.0]])


def test_coefficients_that_depend_on_the_input_are_flown_to_the_fixed_point():
    assert StiffTorque().sdc_residual([0.5, 0.2], [3.0]) < 1e-15
    runs = thetad.compare(controllers=["theta-d", "sdre"], plant=StiffTorque(), initial_state=[0.2, 0.0], duration_s=2,
                          timing=False)
    for run in runs:
        assert run.completed and abs(run.log[-1, 1]) < 0.01, run.reason


def test_optimal_takes_a_python_plant_and_its_jacobian():
    same = dict(horizon=0.5, cost="j", control_interval=0.1, timing=False)
    python = thetad.optimal(controllers=["sdre"], plant=PythonTora(), **same)
    shipped = thetad.optimal(controllers=["sdre"], plant="tora", **same)
    assert python.converged
    gap = python.report["controllers"][0]["gap_percent"]
    assert gap == pytest.approx(shipped.report["controllers"][0]["gap_percent"], rel=1e-9, abs=1e-9)
    with pytest.warns(RuntimeWarning, match="python:Pendulum gives no Jacobian"):
        thetad.optimal(controllers=["sdre"], plant=Pendulum(), initial_state=[0.3, 0.0], **same)


class RaisesInF(Pendulum):
    def f(self, x, u):
        if abs(x[0]) < 0.45:
            raise ZeroDivisionError("the plant gave up")
        return super().f(x, u)


class NanInF(Pendulum):
    def f(self, x, u):
        return [math.nan, 0.0] if abs(x[0]) < 0.45 else super().f(x, u)


class WrongShapeFromSdc(Pendulum):
    def sdc(self, x, u):
        return (np.eye(3), np.ones((3, 1))) if abs(x[0]) < 0.45 else super().sdc(x, u)


class NoPairFromSdc(Pendulum):
    def sdc(self, x, u):
        return np.eye(2) if abs(x[0]) < 0.45 else super().sdc(x, u)


class InfinityInSdc(Pendulum):
    def sdc(self, x, u):
        F, B = super().sdc(x, u)
        return (np.full((2, 2), math.inf), B) if abs(x[0]) < 0.45 else (F, B)


# f is called in the plant's step, sdc by the controller: the reason says which.
@pytest.mark.parametrize("plant, reason", [
    (RaisesInF, "plant failed at t = 0.1690 s: RaisesInF.f raised ZeroDivisionError: the plant gave up"),
    (NanInF, "plant failed at t = 0.1690 s: NanInF.f returned xdot with a NaN or an infinity"),
    (WrongShapeFromSdc, "controller failed at t = 0.1690 s: WrongShapeFromSdc.sdc returned F: expected shape (2, 2), "
                        "got (3, 3)"),
    (NoPairFromSdc, "NoPairFromSdc.sdc must return (F, B), got ndarray"),
    (InfinityInSdc, "InfinityInSdc.sdc returned F with a NaN or an infinity"),
])
def test_what_a_plants_method_raises_or_returns_wrong_ends_the_run_as_failed(plant, reason):
    run = thetad.run(plant=plant(), controller="sdre", **FLIGHT)
    assert run.status == "failed" and run.status_text.startswith("failed at 0.169")
    assert reason in run.reason


def test_a_plant_that_fails_at_the_design_state_raises_before_anything_flies():
    with pytest.raises(thetad.Error, match=r"WrongShapeFromSdc.sdc returned F: expected shape \(2, 2\)"):
        thetad.run(plant=WrongShapeFromSdc(), controller="theta-d", initial_state=[0.1, 0.0], duration_s=1)


def test_what_a_plant_class_gets_wrong_is_named_before_anything_flies():
    class NoDimensions(thetad.Plant):
        def f(self, x, u):
            return x

        def sdc(self, x, u):
            return np.eye(1), np.ones((1, 1))

    class NoSdc(thetad.Plant):
        state_dim, input_dim = 1, 1

        def f(self, x, u):
            return x

    class Misnamed(Pendulum):
        state_names = ["theta"]

    class NamedTwice(Pendulum):
        state_names = [("theta", "rad"), "theta_rad"]

    flight = dict(controller="sdre", initial_state=[0.5, 0.0], duration_s=1)
    with pytest.raises(ValueError, match="NoDimensions.state_dim must be a positive int, got None"):
        thetad.run(plant=NoDimensions(), **flight)
    with pytest.raises(TypeError, match=r"NoSdc does not define sdc\(self, x, u\)"):
        thetad.run(plant=NoSdc(), **flight)
    with pytest.raises(ValueError, match="Misnamed.state_names must be a list of 2 names"):
        thetad.run(plant=Misnamed(), **flight)
    with pytest.raises(ValueError, match="NamedTwice.state_names: two columns would be called theta_rad"):
        thetad.run(plant=NamedTwice(), **flight)
    with pytest.raises(TypeError, match="or a thetad.Plant subclass instance, got int"):
        thetad.run(plant=3, **flight)
    with pytest.raises(thetad.Error, match="python:Pendulum: give initial_state"):
        thetad.run(plant=Pendulum(), controller="sdre", duration_s=1)
    with pytest.raises(thetad.Error, match="lqr-scheduled: flies only the X-Cell helicopter"):
        thetad.run(plant=Pendulum(), controller="lqr-scheduled", initial_state=[0.5, 0.0], duration_s=1)


def test_the_sdc_identity_is_checked_on_request():
    rng = np.random.default_rng(1)
    tora = PythonTora()
    for _ in range(20):
        assert tora.sdc_residual(rng.uniform(-2, 2, 4), rng.uniform(-2, 2, 1)) < 1e-13
    assert Pendulum().sdc_residual([0.5, 0.2]) < 1e-13  # u: the design input, 0

    class Inexact(Pendulum):
        def sdc(self, x, u):
            return np.array([[0.0, 1.0], [self.a, -self.b]]), np.array([[0.0], [1.0]])  # sin θ taken as θ

    assert Inexact().sdc_residual([1.0, 0.0], [0.0]) > 0.1
    with pytest.raises(thetad.Error, match=r"WrongShapeFromSdc.sdc returned F: expected shape \(2, 2\)"):
        WrongShapeFromSdc().sdc_residual([0.1, 0.0], [0.0])


def test_one_python_plant_flies_in_threads_and_is_let_go_after():
    plant = PythonTora()
    references = sys.getrefcount(plant)
    with ThreadPoolExecutor(max_workers=2) as pool:
        runs = list(pool.map(lambda controller: thetad.run(plant=plant, controller=controller, duration_s=1, timing=False),
                             ["sdre", "sdre", "theta-d"]))
    assert all(run.completed for run in runs) and runs[0].summary["cost"] == runs[1].summary["cost"]
    assert sys.getrefcount(plant) == references
