#!/usr/bin/python3
"""Reference solutions of continuous-time algebraic Riccati equations, to 40 significant digits.

For every DIR/NAME.txt written by `care_accuracy write DIR` (bench/care_accuracy.cpp) that has no
DIR/NAME.ref yet: take the double-precision A, B, Q, R as exact, start from scipy's
solve_continuous_are, and run Newton–Kleinman in 50-digit arithmetic (mpmath) until the step is
below 1e-40 of P; each step solves the Lyapunov equation on the n(n+1)/2 unknowns of the
symmetric correction. Writes NAME.ref with P to 25 significant digits. About 15 s per n = 18
problem on one core.

Run with Debian's interpreter (python3-scipy, python3-mpmath):
    /usr/bin/python3 scripts/care_reference.py DIR
"""

import glob
import os
import sys

import mpmath as mp
import numpy as np
import scipy.linalg

mp.mp.dps = 50


def read_matrices(path):
    matrices = {}
    lines = [line for line in open(path) if line.strip() and not line.startswith("#")]
    i = 0
    while i < len(lines):
        name, rows, cols = lines[i].split()
        rows, cols = int(rows), int(cols)
        matrices[name] = np.array([[float(v) for v in lines[i + 1 + r].split()] for r in range(rows)]).reshape(rows, cols)
        i += 1 + rows
    return matrices


def lyapunov(Ac, W, n):
    """X = X' with Ac'X + X Ac + W = 0, on the unknowns x_ij, i <= j."""
    index = {}
    for j in range(n):
        for i in range(j + 1):
            index[(i, j)] = len(index)
    K = mp.zeros(len(index), len(index))
    for (k, l), column in index.items():
        # image of E = e_k e_l' + e_l e_k' under X -> Ac'X + X Ac, entry (i, j)
        for (i, j), row in index.items():
            v = 0
            if j == l:
                v += Ac[k, i]
            if j == k and k != l:
                v += Ac[l, i]
            if i == l:
                v += Ac[k, j]
            if i == k and k != l:
                v += Ac[l, j]
            if v:
                K[row, column] = v
    x = mp.lu_solve(K, mp.matrix([-W[i, j] for (i, j) in index]))
    X = mp.zeros(n, n)
    for (i, j), r in index.items():
        X[i, j] = X[j, i] = x[r]
    return X


def reference(A, B, Q, R):
    n = A.shape[0]
    P = mp.matrix(scipy.linalg.solve_continuous_are(A, B, Q, R).tolist())
    A, B, Q, R = (mp.matrix(M.tolist()) for M in (A, B, Q, R))
    G = B * mp.inverse(R) * B.T
    for _ in range(8):
        residual = A.T * P + P * A - P * G * P + Q
        step = lyapunov(A - G * P, residual, n)
        P = P + step
        if mp.mnorm(step, "f") <= mp.mpf(10) ** -40 * mp.mnorm(P, "f"):
            return P
    sys.exit("care_reference: Newton–Kleinman did not converge")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: /usr/bin/python3 scripts/care_reference.py DIR")
    for path in sorted(glob.glob(os.path.join(sys.argv[1], "*.txt"))):
        out = path[:-4] + ".ref"
        if os.path.exists(out):
            continue
        m = read_matrices(path)
        P = reference(m["A"], m["B"], m["Q"], m["R"])
        n = P.rows
        with open(out + ".tmp", "w") as f:
            f.write("P %d %d\n" % (n, n))
            for i in range(n):
                f.write(" ".join(mp.nstr(P[i, j], 25, strip_zeros=False) for j in range(n)) + "\n")
        os.replace(out + ".tmp", out)
        print(out, flush=True)


if __name__ == "__main__":
    main()
