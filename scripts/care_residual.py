#!/usr/bin/python3
"""The residual of given CARE solutions, evaluated in 40-digit arithmetic.

Reads files in the format of `care_accuracy write` (bench/care_accuracy.cpp): blocks "NAME ROWS
COLS" followed by ROWS lines of numbers, holding A, B, Q, R and any number of solutions whose
block name starts with P. Each P is taken as exact (its double-precision digits) and
‖A'P + PA − P B R⁻¹ B' P + Q‖_F / max(1, ‖Q‖_F) is printed, the formula of
CareResult::relative_residual, with no rounding of its own: what a solver reports can be checked
against it (docs/performance-log.md, "Newton–Kleinman: the residual it reports").

    /usr/bin/python3 scripts/care_residual.py FILE...
"""

import sys

import mpmath as mp

from care_reference import read_matrices

mp.mp.dps = 40


def main():
    if len(sys.argv) < 2:
        sys.exit("usage: /usr/bin/python3 scripts/care_residual.py FILE...")
    for path in sys.argv[1:]:
        # Every double converts to mpf exactly.
        m = {name: mp.matrix(M.tolist()) for name, M in read_matrices(path).items()}
        A, B, Q, R = m["A"], m["B"], m["Q"], m["R"]
        G = B * mp.inverse(R) * B.T
        q_scale = max(mp.mpf(1), mp.mnorm(Q, "f"))
        for name in sorted(k for k in m if k.startswith("P")):
            P = m[name]
            residual = mp.mnorm(A.T * P + P * A - P * G * P + Q, "f") / q_scale
            print("%s %s: relative residual %s" % (path, name, mp.nstr(residual, 3)), flush=True)


if __name__ == "__main__":
    main()
