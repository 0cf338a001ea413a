#!/usr/bin/python3
"""Writes the CAREX reference fixtures used by tests/core/riccati_test.cpp.

Examples of the CAREX collection (Abels & Benner, SLICOT Working Note 1999-14), rebuilt from
their definitions in SLICOT's BB01AD with the default parameters, so that the C++ test reads the
exact same data. The reference solution P comes from an independent solver,
scipy.linalg.solve_continuous_are; where the collection gives the exact solution it is written
too (X_exact), because on the ill-conditioned examples scipy is the less accurate of the two.

Run with Debian's interpreter, whose scipy is the reference:  /usr/bin/python3 scripts/make_carex_fixtures.py
"""

import os
import sys

import numpy as np
import scipy
import scipy.linalg

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "fixtures", "carex")


def ex_1_1():
    A = np.array([[0.0, 1.0], [0.0, 0.0]])
    B = np.array([[0.0], [1.0]])
    Q = np.diag([1.0, 2.0])
    R = np.eye(1)
    X = np.array([[2.0, 1.0], [1.0, 2.0]])
    return "Laub 1979, Ex.1", A, B, Q, R, X


def ex_1_2():
    A = np.array([[4.0, 3.0], [-4.5, -3.5]])
    B = np.array([[1.0], [-1.0]])
    Q = np.array([[9.0, 6.0], [6.0, 4.0]])
    R = np.eye(1)
    X = (1.0 + np.sqrt(2.0)) * Q
    return "Laub 1979, Ex.2: uncontrollable-unobservable data", A, B, Q, R, X


def ex_2_1(eps=1e-6):
    A = np.diag([1.0, -2.0])
    B = np.array([[eps], [0.0]])
    C = np.array([[1.0, 1.0]])
    Q = C.T @ C
    R = np.eye(1)
    t = np.hypot(1.0, eps)
    x12 = 1.0 / (2.0 + t)
    X = np.array([[(1.0 + t) / eps / eps, x12], [x12, (1.0 - eps * x12) * (1.0 + eps * x12) / 4.0]])
    return "Arnold/Laub 1984, Ex.1: (A,B) unstabilizable as eps -> 0, eps = %g" % eps, A, B, Q, R, X


def ex_2_2(eps=1e-8):
    A = np.diag([-0.1, -0.02])
    B = np.array([[0.1, 0.0], [0.001, 0.01]])
    R = np.array([[1.0 + eps, 1.0], [1.0, 1.0]])
    C = np.array([[10.0, 100.0]])
    Q = C.T @ C
    return "Arnold/Laub 1984, Ex.3: R nearly singular as eps -> 0, eps = %g" % eps, A, B, Q, R, None


def ex_2_3(eps=1e6):
    A = np.array([[0.0, eps], [0.0, 0.0]])
    B = np.array([[0.0], [1.0]])
    Q = np.eye(2)
    R = np.eye(1)
    t = np.sqrt(1.0 + 2.0 * eps)
    X = np.array([[t / eps, 1.0], [1.0, t]])
    return "Kenney/Laub/Wette 1989, Ex.2: ill-conditioned as eps -> oo, eps = %g" % eps, A, B, Q, R, X


def ex_2_4(eps=1e-7):
    A = np.array([[eps + 1.0, 1.0], [1.0, eps + 1.0]])
    B = np.eye(2)
    Q = eps * eps * np.eye(2)
    R = np.eye(2)
    t = eps + 1.0
    x11 = (2.0 * t + np.sqrt(2.0) * (np.sqrt(t * t + 1.0) + eps)) / 2.0
    x21 = x11 / (x11 - t)
    X = np.array([[x11, x21], [x21, x11]])
    return "Bai/Qian 1994: ill-conditioned Hamiltonian as eps -> 0, eps = %g" % eps, A, B, Q, R, X


def ex_2_6(eps=1e6):
    V = np.eye(3) - (2.0 / 3.0) * np.ones((3, 3))
    A = V @ np.diag([eps, 2.0 * eps, 3.0 * eps]) @ V
    B = np.eye(3)
    R = eps * np.eye(3)
    Q = V @ np.diag([1.0 / eps, 1.0, eps]) @ V
    e2 = eps * eps
    X = V @ np.diag([e2 + np.sqrt(e2 * e2 + 1.0), 2.0 * e2 + np.sqrt(4.0 * e2 * e2 + eps),
                     3.0 * e2 + eps * np.sqrt(9.0 * e2 + 1.0)]) @ V
    return "Petkov et al. 1987: badly scaled Hamiltonian as eps -> oo, eps = %g" % eps, A, B, Q, R, X


def ex_2_7(eps=1e-6):
    A = np.zeros((4, 4))
    A[0, 1] = 0.400
    A[1, 2] = 0.345
    A[2, 1] = -0.524 / eps
    A[2, 2] = -0.465 / eps
    A[2, 3] = 0.262 / eps
    A[3, 3] = -1.0 / eps
    B = np.zeros((4, 1))
    B[3, 0] = 1.0 / eps
    C = np.zeros((2, 4))
    C[0, 0] = 1.0
    C[1, 2] = 1.0
    Q = C.T @ C
    R = np.eye(1)
    return "Chow/Kokotovic 1976: magnetic tape control, eps = %g" % eps, A, B, Q, R, None


def ex_2_8(eps=1e-6):
    A = np.array([[-eps, 1.0, 0.0, 0.0], [-1.0, -eps, 0.0, 0.0],
                  [0.0, 0.0, eps, 1.0], [0.0, 0.0, -1.0, eps]])
    B = np.ones((4, 1))
    C = np.ones((1, 4))
    Q = C.T @ C
    R = np.eye(1)
    return "Arnold/Laub 1984, Ex.2: poor separation of the closed-loop spectrum, eps = %g" % eps, A, B, Q, R, None


def ex_3_1(vehicles=20):
    n = 2 * vehicles - 1
    A = np.zeros((n, n))
    B = np.zeros((n, vehicles))
    C = np.zeros((vehicles - 1, n))
    for i in range(1, n + 1):  # 1-based as in the collection
        if i % 2 == 1:
            A[i - 1, i - 1] = -1.0
            B[i - 1, (i + 1) // 2 - 1] = 1.0
        else:
            A[i - 1, i - 2] = 1.0
            A[i - 1, i] = -1.0
            C[i // 2 - 1, i - 1] = 1.0
    Q = 10.0 * C.T @ C
    R = np.eye(vehicles)
    return "Laub 1979, Ex.4: string of %d high speed vehicles" % vehicles, A, B, Q, R, None


def ex_3_2(n=64):
    A = -2.0 * np.eye(n) + np.eye(n, k=1) + np.eye(n, k=-1)
    A[0, n - 1] = 1.0
    A[n - 1, 0] = 1.0
    B = np.eye(n)
    Q = np.eye(n)
    R = np.eye(n)
    theta = 2.0 * np.pi / n
    c = np.cos(theta * np.arange(n))
    lam = -2.0 + 2.0 * c + np.sqrt(5.0 + 4.0 * c * (c - 2.0))
    first = np.array([np.dot(lam, np.cos(theta * np.arange(n) * j)) / n for j in range(n)])
    X = np.array([[first[(i - j) % n] for j in range(n)] for i in range(n)])
    return "Laub 1979, Ex.5: circulant matrices, n = %d" % n, A, B, Q, R, X


def ex_4_1(n=21, q=1.0, r=1.0):
    A = np.eye(n, k=1)
    B = np.zeros((n, 1))
    B[n - 1, 0] = 1.0
    Q = np.zeros((n, n))
    Q[0, 0] = q
    R = r * np.eye(1)
    return "Laub 1979, Ex.6: ill-conditioned Riccati equation, n = %d" % n, A, B, Q, R, None


EXAMPLES = {
    "1_1": ex_1_1, "1_2": ex_1_2, "2_1": ex_2_1, "2_2": ex_2_2, "2_3": ex_2_3, "2_4": ex_2_4,
    "2_6": ex_2_6, "2_7": ex_2_7, "2_8": ex_2_8, "3_1": ex_3_1, "3_2": ex_3_2, "4_1": ex_4_1,
}


def write_matrix(f, name, M):
    f.write("%s %d %d\n" % (name, M.shape[0], M.shape[1]))
    for row in M:
        f.write(" ".join("%.17g" % v for v in row) + "\n")


def residual(A, B, Q, R, X):
    G = B @ np.linalg.solve(R, B.T)
    res = A.T @ X + X @ A - X @ G @ X + Q
    return np.linalg.norm(res) / max(1.0, np.linalg.norm(Q))


def main():
    os.makedirs(OUT, exist_ok=True)
    for key, make in EXAMPLES.items():
        title, A, B, Q, R, X = make()
        P = scipy.linalg.solve_continuous_are(A, B, Q, R)
        P = 0.5 * (P + P.T)
        path = os.path.join(OUT, "carex_%s.txt" % key)
        with open(path, "w") as f:
            f.write("# CAREX %s: %s\n" % (key.replace("_", "."), title))
            f.write("# made by scripts/make_carex_fixtures.py; P from scipy %s solve_continuous_are\n"
                    % scipy.__version__)
            f.write("# scipy relative residual %.3g%s\n" % (
                residual(A, B, Q, R, P),
                "" if X is None else ", exact-solution relative residual %.3g, "
                "scipy relative error %.3g" % (residual(A, B, Q, R, X),
                                                np.linalg.norm(P - X) / np.linalg.norm(X))))
            f.write("name carex_%s\nn %d\nm %d\n" % (key, A.shape[0], B.shape[1]))
            write_matrix(f, "A", A)
            write_matrix(f, "B", B)
            write_matrix(f, "Q", Q)
            write_matrix(f, "R", R)
            write_matrix(f, "P", P)
            if X is not None:
                write_matrix(f, "X_exact", X)
        print("%s: n=%d m=%d  %s" % (path, A.shape[0], B.shape[1], open(path).readlines()[2].strip()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
