"""The helicopter from Python: f, the SDC factorization, trims, switches and seeded draws."""

import numpy as np
import pytest

import thetad


def test_names_and_dimensions():
    plant = thetad.Helicopter()
    assert plant.state_dim == 18 and plant.input_dim == 5
    assert thetad.state_names[:3] == ["x_p", "y_p", "z_p"] and thetad.state_names[-1] == "s"
    assert thetad.input_names == ["T_mr", "delta_ped", "delta_col", "delta_lon", "delta_lat"]
    assert thetad.Helicopter.state_names == thetad.state_names


def test_hover_trim_is_an_equilibrium(hover_trim):
    plant = thetad.Helicopter()
    assert hover_trim.residual < 1e-8
    np.testing.assert_allclose(hover_trim.state[:3], [0.0, 0.0, -3.5])
    np.testing.assert_allclose(plant.f(hover_trim.state, hover_trim.input)[:14], 0.0, atol=1e-7)
    assert 70.0 < hover_trim.input[0] < 90.0  # about m g of thrust


def test_sdc_factorizes_f_exactly(hover_trim):
    plant = thetad.Helicopter()
    rng = np.random.default_rng(3)
    for _ in range(5):
        x = hover_trim.state + 0.05 * rng.standard_normal(18)
        x[17] = 1.0
        u = hover_trim.input + 0.01 * rng.standard_normal(5)
        F, B = plant.sdc(x, u)
        assert F.shape == (18, 18) and B.shape == (18, 5)
        np.testing.assert_allclose(F @ x + B @ u, plant.f(x, u), rtol=1e-12, atol=1e-10)


def test_a_seed_draws_the_parameters_a_run_flies(hover_trim):
    rows = thetad.uncertainty_draw(7)
    assert len(rows) == 45 and rows == thetad.uncertainty_draw(7) and rows != thetad.uncertainty_draw(8)
    parameters = [row for row in rows if row["category"] == "parameter"]
    assert len(parameters) == 21
    assert all(abs(row["factor"] - 1.0) <= row["percent"] / 100.0 for row in parameters)
    drawn = thetad.Helicopter(seed=7)
    x, u = hover_trim.state, hover_trim.input
    assert not np.allclose(drawn.f(x, u), thetad.Helicopter().f(x, u))
    np.testing.assert_array_equal(drawn.f(x, u), thetad.Helicopter(seed=7).f(x, u))
    # The run with that seed reports the same factors.
    result = thetad.run("hover-step", "lqr", seed=7, duration_s=0.01, summary_only=True)
    reported = result.summary["parameter_factors"]
    for row in parameters:
        assert reported[row["name"]] == pytest.approx(row["factor"], rel=1e-15)


def test_presets_and_switches():
    assert thetad.Helicopter().options["rotor_speed_model"] == "thrust_inversion"
    assert thetad.Helicopter(rotor_speed_model="governor").options["rotor_speed_model"] == "governor"
    assert thetad.Helicopter("paper", horizontal_tail_sign=1).options["horizontal_tail_sign"] == "+1"
    assert thetad.Helicopter(collective_trim_offset=False).options["collective_trim_offset"] == "off"
    assert thetad.Helicopter("paper").options != thetad.Helicopter().options
    with pytest.raises(thetad.Error, match="preset"):
        thetad.Helicopter("literal")
    with pytest.raises(thetad.Error, match="rotor_speed_modle"):
        thetad.Helicopter(rotor_speed_modle="governor")
    with pytest.raises(TypeError, match="solidity"):
        thetad.Helicopter(solidity=0.03)


def test_wrong_state_shapes(hover_trim):
    plant = thetad.Helicopter()
    with pytest.raises(ValueError, match=r"Helicopter.f: x: expected shape \(18,\), got \(17,\)"):
        plant.f(np.zeros(17), hover_trim.input)
    with pytest.raises(ValueError, match=r"Helicopter.sdc: u: expected shape \(5,\), got \(5, 1\)"):
        plant.sdc(hover_trim.state, hover_trim.input.reshape(5, 1))
    with pytest.raises(TypeError, match="Helicopter.f: u"):
        plant.f(hover_trim.state, "u")


def test_linearize_is_the_exact_jacobian(hover_trim):
    """thetad.linearize's A, B (the plant's hand Jacobian) against central differences of f from Python,
    at the hover trim and at disturbed states."""
    plant = thetad.Helicopter()
    rng = np.random.default_rng(8)
    for step in (0.0, 0.05):
        x = hover_trim.state + step * rng.standard_normal(18)
        x[17] = 1.0
        u = hover_trim.input * (1.0 + step * rng.standard_normal(5))
        linear = thetad.linearize(plant, x, u)
        A, B = linear
        assert A.shape == (18, 18) and B.shape == (18, 5)
        assert repr(linear) == "Linearization(n=18, m=5)"
        z = np.concatenate([x, u])
        columns = []
        for j in range(23):
            h = 1e-6 * max(1.0, abs(z[j]))
            forward, backward = z.copy(), z.copy()
            forward[j] += h
            backward[j] -= h
            columns.append((plant.f(forward[:18], forward[18:]) - plant.f(backward[:18], backward[18:])) / (2 * h))
        J = np.array(columns).T
        scale = np.maximum(1.0, np.abs(np.hstack([A, B])))
        assert np.max(np.abs(np.hstack([A, B]) - J) / scale) < 1e-6
    with pytest.raises(ValueError, match=r"linearize: u: expected shape \(5,\)"):
        thetad.linearize(plant, x, np.zeros(4))


def test_design_defaults_have_names_and_still_unpack():
    plant = thetad.Helicopter()
    defaults = plant.design_defaults()
    q, r, u0 = defaults
    np.testing.assert_array_equal(q, defaults.state_weights)
    np.testing.assert_array_equal(r, defaults.input_weights)
    np.testing.assert_array_equal(u0, defaults.input)
    assert q.shape == (18,) and r.shape == (5,) and u0.shape == (5,)
    assert repr(defaults).startswith("DesignDefaults(state_weights=array([")


def test_reprs_say_what_an_object_is(hover_trim):
    assert repr(thetad.Helicopter()).startswith("Helicopter({")
    assert repr(hover_trim).startswith("Trim(input=array([")
    built = thetad.controller("theta-d", label="mine")
    assert repr(built) == "RegisteredController(label='mine', controller='theta-d')"


def test_demo_gives_what_thetad_demo_writes():
    """The diagnostics of `thetad demo` from the library: the CARE at the initial state solved to
    rounding level, Newton-Kleinman agreeing with it, and a hover trim that holds m g of thrust
    at about 172 rad/s (docs/model.md §8.1, §4.2)."""
    demo = thetad.demo()
    assert list(demo) == ["riccati", "newton_kleinman", "hover_trim", "build"]
    riccati = demo["riccati"]
    assert (riccati["n"], riccati["m"]) == (18, 5)
    assert riccati["relative_residual"] < 1e-10
    assert riccati["slowest_closed_loop_real_part"] < 0
    assert min(riccati["diag_T0"]) > 0
    assert demo["newton_kleinman"]["relative_difference_to_schur"] < 1e-10
    trim = demo["hover_trim"]
    mass_times_gravity = thetad.Helicopter().design_defaults().input[0]
    assert trim["residual"] < 1e-8
    assert abs(trim["input"][0] - mass_times_gravity) < 0.02 * mass_times_gravity
    assert 165 < trim["rotor_speed_rad_s"] < 180
    assert demo["build"]["thetad_version"] == thetad.__version__
