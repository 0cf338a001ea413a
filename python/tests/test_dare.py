"""dare and dlqr (structure-preserving doubling, core/dare.hpp) against scipy, closed forms and the
errors a wrong call gets."""

import numpy as np
import pytest
import scipy.linalg

import thetad


def random_problems(seed=17):
    """Stabilizable problems from n = 2 to 40 with unstable open loops (a random B of full column
    rank reaches every mode almost surely), optionally with a cross term that keeps the cost convex."""
    rng = np.random.default_rng(seed)
    for n in (2, 3, 5, 8, 13, 20, 30, 40):
        m = 1 + n // 4
        A = 1.3 * rng.standard_normal((n, n)) / np.sqrt(n)
        B = rng.standard_normal((n, m))
        C = rng.standard_normal((n, n))
        G = rng.standard_normal((m, m))
        R = G @ G.T + np.eye(m)
        S = 0.2 * rng.standard_normal((n, m))
        Q = C.T @ C + S @ np.linalg.solve(R, S.T)
        yield A, B, Q, R, S


def test_dare_agrees_with_scipy():
    for A, B, Q, R, S in random_problems():
        for cross in (None, S):
            result = thetad.dare(A, B, Q, R, cross)
            X_scipy = scipy.linalg.solve_discrete_are(A, B, Q, R, s=cross)
            np.testing.assert_allclose(result.X, X_scipy, rtol=1e-8, atol=1e-9 * np.linalg.norm(X_scipy))
            np.testing.assert_array_equal(result.X, result.X.T)
            assert np.all(np.abs(result.eigenvalues) < 1)
            n = A.shape[0]
            terms = np.linalg.norm(Q) + np.linalg.norm(A) ** 2 * np.linalg.norm(result.X) + np.linalg.norm(result.X)
            assert result.residual * max(1.0, np.linalg.norm(Q)) <= 10 * n * np.finfo(float).eps * terms
            assert 0 < result.doublings < 64


def test_dlqr_returns_k_s_e_as_python_control():
    for A, B, Q, R, N in random_problems(seed=4):
        K, S, E = thetad.dlqr(A, B, Q, R, N)
        X = scipy.linalg.solve_discrete_are(A, B, Q, R, s=N)
        np.testing.assert_allclose(S, X, rtol=1e-8, atol=1e-9 * np.linalg.norm(X))
        np.testing.assert_allclose(K, np.linalg.solve(R + B.T @ X @ B, B.T @ X @ A + N.T), rtol=1e-7,
                                   atol=1e-8 * np.linalg.norm(K))
        np.testing.assert_allclose(np.sort_complex(E), np.sort_complex(np.linalg.eigvals(A - B @ K)), atol=1e-8)


def test_scalar_dare_has_its_closed_form():
    a, b, q, r = 1.2, 0.5, 2.0, 0.7
    p = r * (1 - a * a) - q * b * b
    x = (-p + np.sqrt(p * p + 4 * b * b * q * r)) / (2 * b * b)
    result = thetad.dare([[a]], [[b]], [[q]], [[r]])
    assert result.X[0, 0] == pytest.approx(x, rel=1e-15)
    assert repr(result).startswith("DareResult(n=1, m=1, residual=")


def test_discretized_double_integrator_dlqr_is_stabilizing():
    h = 0.1
    A = np.array([[1.0, h], [0.0, 1.0]])
    B = np.array([[h * h / 2], [h]])
    K, S, E = thetad.dlqr(A, B, np.eye(2), np.eye(1))
    np.testing.assert_allclose(S, scipy.linalg.solve_discrete_are(A, B, np.eye(2), np.eye(1)), rtol=1e-10)
    assert np.all(np.abs(E) < 1) and K.shape == (1, 2)


def test_errors_name_the_reason():
    with pytest.raises(thetad.Error, match="DARE: the pair \\(A, B\\) is not stabilizable"):
        thetad.dare(np.diag([2.0, 0.5]), [[0.0], [1.0]], np.eye(2), np.eye(1))
    with pytest.raises(thetad.Error, match="DARE: R is singular"):
        thetad.dare([[2.0, -1.0], [1.0, 0.0]], [[1.0], [0.0]], [[0.0, 0.0], [0.0, 1.0]], [[0.0]])
    with pytest.raises(ValueError, match=r"dare: S: expected shape \(2, 1\)"):
        thetad.dare(np.eye(2), np.ones((2, 1)), np.eye(2), np.eye(1), np.ones((2, 2)))
    with pytest.raises(ValueError, match=r"dlqr: R: expected shape \(1, 1\)"):
        thetad.dlqr(np.eye(2), np.ones((2, 1)), np.eye(2), np.eye(2))
