#!/usr/bin/python3
"""Plots the sigma_max curves that `thetad tune` writes (<out>/sigma-curves.csv): sigma_max of the
SDRE's P and of the theta-D series with the default and the tuned k_i, l_i over time (top), and
their relative differences to the SDRE (bottom, where the fit's effect is visible: the three
curves of the top panel agree to about 1e-5).

  MPLBACKEND=Agg /usr/bin/python3 scripts/plot_tuning.py OUT/sigma-curves.csv docs/figures/tuning-sigma.png

Needs Debian's python3-matplotlib (hence /usr/bin/python3). Errors: one line on stderr starting
with "plot_tuning.py:", exit status 1.
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

COLUMNS = ["t_s", "sigma_sdre", "sigma_theta_d_default", "sigma_theta_d_tuned"]


def main(argv):
    if len(argv) != 3:
        raise ValueError("usage: plot_tuning.py SIGMA_CURVES_CSV IMAGE")
    source, image = argv[1], argv[2]
    with open(source) as f:
        header = f.readline().strip().split(",")
    if header != COLUMNS:
        raise ValueError(f"{source}: expected the columns {','.join(COLUMNS)}, got {','.join(header)}")
    data = np.loadtxt(source, delimiter=",", skiprows=1, ndmin=2)
    t, sdre, default, tuned = data.T

    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(9, 6.5))
    top.plot(t, sdre, label="SDRE  $\\sigma_{max}(P)$", color="black", linewidth=1.6)
    top.plot(t, default, label="θ–D default (k = l = 1)", color="tab:blue", linestyle="--")
    top.plot(t, tuned, label="θ–D tuned", color="tab:red", linestyle=":")
    top.set_ylabel("$\\sigma_{max}$")
    top.legend(loc="best")
    top.grid(True, alpha=0.3)
    bottom.plot(t, (default - sdre) / sdre, label="default", color="tab:blue")
    bottom.plot(t, (tuned - sdre) / sdre, label="tuned", color="tab:red")
    bottom.set_ylabel("$(\\sigma_{θD} - \\sigma_{SDRE}) / \\sigma_{SDRE}$")
    bottom.set_xlabel("t (s)")
    bottom.legend(loc="best")
    bottom.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(image, dpi=120)


if __name__ == "__main__":
    try:
        main(sys.argv)
    except (OSError, ValueError) as error:
        print(f"plot_tuning.py: {error}", file=sys.stderr)
        sys.exit(1)
