"""care, lqr and lyap against scipy, and the errors a wrong call gets."""

import numpy as np
import pytest
import scipy.linalg

import thetad

METHODS = ["automatic", "matrix_sign", "schur"]


def random_problems(count, seed=11):
    """Stabilizable, detectable problems of a few sizes (a random B of full column rank controls
    almost surely) with scipy's solution, where scipy succeeds."""
    rng = np.random.default_rng(seed)
    problems = []
    for n, m in [(2, 1), (4, 2), (6, 3), (10, 4), (18, 5)] * (count // 5):
        A = rng.standard_normal((n, n))
        B = rng.standard_normal((n, m))
        C = rng.standard_normal((n, n))
        Q = C.T @ C + 1e-3 * np.eye(n)
        G = rng.standard_normal((m, m))
        R = G @ G.T + np.eye(m)
        try:
            P = scipy.linalg.solve_continuous_are(A, B, Q, R)
        except (np.linalg.LinAlgError, ValueError):
            continue
        problems.append((A, B, Q, R, P))
    return problems


def hover_problem():
    """The paper-sized problem: the helicopter's SDC at hover with the paper's weights."""
    plant = thetad.Helicopter()
    trim = plant.trim(altitude=3.5)
    F, B = plant.sdc(trim.state, trim.input)
    q, r, _ = plant.design_defaults()
    return F, B, np.diag(q), np.diag(r)


@pytest.mark.parametrize("method", METHODS)
def test_care_agrees_with_scipy(method):
    problems = random_problems(20)
    assert len(problems) >= 15
    for A, B, Q, R, P_scipy in problems:
        result = thetad.care(A, B, Q, R, method=method)
        scale = max(1.0, np.linalg.norm(P_scipy))
        assert np.linalg.norm(result.P - P_scipy) <= 1e-8 * scale
        np.testing.assert_allclose(result.K, np.linalg.solve(R, B.T @ result.P), rtol=1e-9, atol=1e-9 * scale)
        assert np.all(result.eigenvalues.real < 0)
        assert result.residual < 1e-10


def test_care_estimates_are_off_unless_asked_for():
    """forward_error and condition: NaN by default; with estimates=True the forward-error estimate of a
    well-conditioned problem (CAREX 1.1: P = [[2, 1], [1, 2]] exactly) is at rounding level."""
    A = np.array([[0.0, 1.0], [0.0, 0.0]])
    B = np.array([[0.0], [1.0]])
    Q = np.diag([1.0, 2.0])
    R = np.eye(1)
    plain = thetad.care(A, B, Q, R)
    assert np.isnan(plain.forward_error) and np.isnan(plain.condition)
    estimated = thetad.care(A, B, Q, R, estimates=True)
    np.testing.assert_array_equal(estimated.P, plain.P)
    error = np.linalg.norm(estimated.P - np.array([[2.0, 1.0], [1.0, 2.0]])) / np.linalg.norm([[2.0, 1.0], [1.0, 2.0]])
    assert error / 10 <= estimated.forward_error <= 1e-14
    assert 0 < estimated.condition < 1e3


def test_lqr_on_the_helicopter_agrees_with_scipy():
    F, B, Q, R = hover_problem()
    P_scipy = scipy.linalg.solve_continuous_are(F, B, Q, R)
    K, P, eigenvalues = thetad.lqr(F, B, Q, R)
    assert np.linalg.norm(P - P_scipy) <= 1e-6 * np.linalg.norm(P_scipy)
    assert K.shape == (5, 18) and P.shape == (18, 18) and eigenvalues.shape == (18,)
    np.testing.assert_array_equal(P, P.T)
    closed_loop = np.linalg.eigvals(F - B @ K)
    np.testing.assert_allclose(np.sort_complex(closed_loop), np.sort_complex(eigenvalues), rtol=1e-6, atol=1e-9)


def test_lqr_of_the_double_integrator_is_the_textbook_gain():
    A = np.array([[0.0, 1.0], [0.0, 0.0]])
    B = np.array([[0.0], [1.0]])
    K, P, _ = thetad.lqr(A, B, np.eye(2), np.eye(1))
    np.testing.assert_allclose(K, [[1.0, np.sqrt(3.0)]], rtol=1e-12)


def test_fortran_and_c_ordered_inputs_give_the_same_answer():
    A, B, Q, R, _ = random_problems(5)[2]
    c = thetad.care(np.ascontiguousarray(A), B, Q, R)
    f = thetad.care(np.asfortranarray(A), np.asfortranarray(B), np.asfortranarray(Q), np.asfortranarray(R))
    np.testing.assert_array_equal(c.P, f.P)
    # Lists and integer arrays convert.
    d = thetad.care(A.tolist(), B.tolist(), Q.tolist(), R.tolist())
    np.testing.assert_array_equal(c.P, d.P)
    # The result's matrices are read-only views of the C++ result, not copies.
    assert c.P.dtype == np.float64 and not c.P.flags.writeable and not c.P.flags.owndata


def test_unstabilizable_pair_raises_with_the_uncontrollable_mode():
    A = np.diag([1.0, 2.0])
    B = np.array([[1.0], [0.0]])
    for method in METHODS:
        with pytest.raises(thetad.Error, match="stabiliz"):
            thetad.care(A, B, np.eye(2), np.eye(1), method=method)


def test_lyap_agrees_with_scipy():
    rng = np.random.default_rng(5)
    for n in (1, 3, 8, 18):
        A = rng.standard_normal((n, n)) - 2.0 * n * np.eye(n)
        W = rng.standard_normal((n, n))
        Q = W @ W.T
        X = thetad.lyap(A, Q)
        # A'X + XA + Q = 0 is scipy's A X + X A^H = Q with A -> A', Q -> -Q.
        np.testing.assert_allclose(X, scipy.linalg.solve_continuous_lyapunov(A.T, -Q), rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(A.T @ X + X @ A + Q, 0.0, atol=1e-9 * np.linalg.norm(Q))


def test_lyap_refuses_a_singular_operator():
    with pytest.raises(thetad.Error, match="singular"):
        thetad.lyap(np.diag([1.0, -1.0]), np.eye(2))


@pytest.mark.parametrize(
    "arguments, expected",
    [
        ((np.zeros((2, 3)), np.ones((2, 1)), np.eye(2), np.eye(1)), r"care: A: expected a square shape \(n, n\), got \(2, 3\)"),
        ((np.eye(2), np.ones((3, 1)), np.eye(2), np.eye(1)), r"care: B: expected shape \(2, m\), got \(3, 1\)"),
        ((np.eye(2), np.ones((2, 1)), np.eye(3), np.eye(1)), r"care: Q: expected shape \(2, 2\), got \(3, 3\)"),
        ((np.eye(2), np.ones((2, 1)), np.eye(2), np.eye(2)), r"care: R: expected shape \(1, 1\), got \(2, 2\)"),
        ((np.eye(2), np.ones(2), np.eye(2), np.eye(1)), r"care: B: expected shape \(2, m\), got \(2,\)"),
    ],
)
def test_wrong_shapes_raise_value_error_naming_the_expected_shape(arguments, expected):
    with pytest.raises(ValueError, match=expected):
        thetad.care(*arguments)


def test_wrong_types_raise_type_error():
    with pytest.raises(TypeError, match="care: A: expected a real matrix"):
        thetad.care("not a matrix", np.ones((2, 1)), np.eye(2), np.eye(1))
    with pytest.raises(TypeError, match="care: Q: expected a real matrix"):
        thetad.care(np.eye(2), np.ones((2, 1)), np.eye(2) * 1j, np.eye(1))
    with pytest.raises(TypeError, match="lyap: Q"):
        thetad.lyap(np.eye(2), None)
    with pytest.raises(ValueError, match="method 'qz' is unknown"):
        thetad.care(np.eye(2), np.ones((2, 1)), np.eye(2), np.eye(1), method="qz")


def test_non_finite_entries_raise_the_library_error():
    A = np.eye(2)
    A[0, 1] = np.nan
    with pytest.raises(thetad.Error, match="finite"):
        thetad.care(A, np.ones((2, 1)), np.eye(2), np.eye(1))


def test_lqr_with_a_cross_term_agrees_with_scipy():
    """The cost x'Qx + u'Ru + 2x'Nu: scipy's solve_continuous_are(..., s=N), K = R⁻¹(B'P + N')."""
    rng = np.random.default_rng(3)
    for n, m in [(2, 1), (5, 2), (12, 4)]:
        A = rng.standard_normal((n, n))
        B = rng.standard_normal((n, m))
        N = 0.3 * rng.standard_normal((n, m))
        R = np.eye(m)
        Q = N @ np.linalg.solve(R, N.T) + np.eye(n)  # Q − NR⁻¹N' = I: a convex cost
        K, P, eigenvalues = thetad.lqr(A, B, Q, R, N)
        P_scipy = scipy.linalg.solve_continuous_are(A, B, Q, R, s=N)
        np.testing.assert_allclose(P, P_scipy, rtol=1e-9, atol=1e-10 * np.linalg.norm(P_scipy))
        np.testing.assert_allclose(K, np.linalg.solve(R, B.T @ P_scipy + N.T), rtol=1e-8, atol=1e-9)
        np.testing.assert_allclose(np.sort_complex(eigenvalues), np.sort_complex(np.linalg.eigvals(A - B @ K)),
                                   rtol=1e-8, atol=1e-9)
    with pytest.raises(ValueError, match=r"lqr: N: expected shape \(2, 1\), got \(1, 2\)"):
        thetad.lqr(np.eye(2), np.ones((2, 1)), np.eye(2), np.eye(1), np.ones((1, 2)))
