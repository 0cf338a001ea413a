#!/usr/bin/python3
"""Writes the fixtures of tests/core/care_estimates_test.cpp: CARE problems with 40-digit solutions.

Each tests/fixtures/care_reference/NAME.txt holds A, B, Q, R and P_exact, the stabilizing solution
of the double-precision data taken as exact, from scripts/care_reference.py (Newton's iteration
with the residual in 50-digit arithmetic), written to 25 significant digits. The problems:
- every CAREX example of tests/fixtures/carex (scripts/make_carex_fixtures.py);
- some of the accuracy study's (bench/care_accuracy.cpp), given as DIR: the paper's problem, random
  ones with the paper's weight spread, badly scaled ones and one with Q = I, R = I.

Run with Debian's interpreter (python3-scipy, python3-mpmath), after `care_accuracy write DIR`:
    /usr/bin/python3 scripts/make_care_reference_fixtures.py DIR
"""

import glob
import os
import sys

import mpmath as mp
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import care_reference  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
OUT = os.path.join(ROOT, "tests", "fixtures", "care_reference")
STUDY = ["paper_n18_m5", "n12_m4_0", "n18_m5_0", "n18_m5_6", "n36_m10_0", "scaled_n10_m3_0", "scaled_n10_m3_3",
         "scaled_n18_m5_0", "unit_n18_m6_0"]


def read_blocks(path):
    """The matrix blocks 'NAME ROWS COLS' of a fixture or a care_accuracy problem; other lines skipped."""
    matrices = {}
    lines = [line.split() for line in open(path) if line.strip() and not line.startswith("#")]
    i = 0
    while i < len(lines):
        fields = lines[i]
        if len(fields) == 3 and fields[0][0].isupper():
            rows, cols = int(fields[1]), int(fields[2])
            matrices[fields[0]] = np.array([[float(v) for v in lines[i + 1 + r]] for r in range(rows)]).reshape(rows, cols)
            i += 1 + rows
        else:
            i += 1
    return matrices


def write_fixture(name, source, m, P):
    path = os.path.join(OUT, name + ".txt")
    with open(path + ".tmp", "w") as f:
        f.write("# %s (%s); P_exact to 25 digits from scripts/care_reference.py,\n" % (name, source))
        f.write("# written by scripts/make_care_reference_fixtures.py\n")
        f.write("name %s\nn %d\nm %d\n" % (name, m["A"].shape[0], m["B"].shape[1]))
        for key in ("A", "B", "Q", "R"):
            M = m[key]
            f.write("%s %d %d\n" % (key, M.shape[0], M.shape[1]))
            for row in M:
                f.write(" ".join("%.17g" % v for v in row) + "\n")
        f.write("P_exact %d %d\n" % (P.rows, P.cols))
        for i in range(P.rows):
            f.write(" ".join(mp.nstr(P[i, j], 25, strip_zeros=False) for j in range(P.cols)) + "\n")
    os.replace(path + ".tmp", path)
    print(path, flush=True)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: /usr/bin/python3 scripts/make_care_reference_fixtures.py DIR  (from care_accuracy write DIR)")
    os.makedirs(OUT, exist_ok=True)
    sources = [(p, "CAREX, tests/fixtures/carex") for p in sorted(glob.glob(os.path.join(ROOT, "tests", "fixtures", "carex", "*.txt")))]
    sources += [(os.path.join(sys.argv[1], name + ".txt"), "care_accuracy write") for name in STUDY]
    for path, source in sources:
        m = read_blocks(path)
        P = care_reference.reference(m["A"], m["B"], m["Q"], m["R"])
        write_fixture(os.path.splitext(os.path.basename(path))[0], source, m, P)


if __name__ == "__main__":
    main()
