#!/usr/bin/python3
"""Reference solutions of continuous-time algebraic Riccati equations, to 40 significant digits.

For every DIR/NAME.txt written by `care_accuracy write DIR` (bench/care_accuracy.cpp) that has no
DIR/NAME.ref yet: take the double-precision A, B, Q, R as exact, start from scipy's
solve_continuous_are, and run Newton's iteration with the residual in 50-digit arithmetic (mpmath)
until the step is below 1e-40 of P. Up to n = 10 each step solves the Lyapunov equation on the
n(n+1)/2 unknowns of the symmetric correction in 50 digits too; above, the correction is solved in
double precision (scipy), which is iterative refinement: the residual is exact to 50 digits, so a
correction accurate to a few digits still shrinks the error by that many digits per step, and the
loop ends only when the 50-digit step itself is below 1e-40 of P. Writes NAME.ref with P to 25
significant digits. Seconds per problem at n = 18, about a minute at n = 64, on one core.

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


def to_float(M):
    return np.array(M.tolist(), dtype=float)


def correction(Ac, W, n):
    """X = X' with Ac'X + X Ac + W = 0: in 50 digits up to n = 10, in double precision above."""
    if n <= 10:
        return lyapunov(Ac, W, n)
    X = scipy.linalg.solve_continuous_lyapunov(to_float(Ac).T, -to_float(W))
    return mp.matrix((0.5 * (X + X.T)).tolist())


def reference(A, B, Q, R):
    """The stabilizing solution of A'P + PA − PBR⁻¹B'P + Q = 0 to 40 digits, the data taken as exact."""
    n = A.shape[0]
    P = mp.matrix(scipy.linalg.solve_continuous_are(A, B, Q, R).tolist())
    A, B, Q, R = (mp.matrix(M.tolist()) for M in (A, B, Q, R))
    G = B * mp.inverse(R) * B.T
    for _ in range(60):
        residual = A.T * P + P * A - P * G * P + Q
        step = correction(A - G * P, residual, n)
        P = P + step
        if mp.mnorm(step, "f") <= mp.mpf(10) ** -40 * mp.mnorm(P, "f"):
            return P
    sys.exit("care_reference: Newton's iteration did not converge")


def write_reference(path, P):
    """P to 25 significant digits as a block 'P n n', written atomically."""
    n = P.rows
    with open(path + ".tmp", "w") as f:
        f.write("P %d %d\n" % (n, n))
        for i in range(n):
            f.write(" ".join(mp.nstr(P[i, j], 25, strip_zeros=False) for j in range(n)) + "\n")
    os.replace(path + ".tmp", path)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: /usr/bin/python3 scripts/care_reference.py DIR")
    for path in sorted(glob.glob(os.path.join(sys.argv[1], "*.txt"))):
        out = path[:-4] + ".ref"
        if os.path.exists(out):
            continue
        m = read_matrices(path)
        write_reference(out, reference(m["A"], m["B"], m["Q"], m["R"]))
        print(out, flush=True)


if __name__ == "__main__":
    main()
