"""The figure of the σmax fit (`thetad tune`, docs/tuning.md): σmax of the SDRE's P and of the θ–D
series with the default and the tuned k_i, l_i over time (top), and their relative differences to
the SDRE (bottom, where the fit's effect shows: the three curves of the top panel agree to ~1e-5).
"""

import numpy as np

from . import style
from .results import PlotError
from .style import plt

COLUMNS = ["t_s", "sigma_sdre", "sigma_theta_d_default", "sigma_theta_d_tuned"]
# The SDRE is what the series approximates: it keeps its controller look; the two θ–D series are
# told apart by the spare looks.
CURVES = ["sdre", "θ–D default (k = l = 1)", "θ–D tuned"]


def read_curves(source):
    """(t, σ SDRE, σ θ–D default, σ θ–D tuned) of a sigma-curves.csv."""
    try:
        with open(source, encoding="utf-8") as f:
            header = f.readline().strip().split(",")
        if header != COLUMNS:
            raise PlotError(f"{source}: expected the columns {','.join(COLUMNS)}, got {','.join(header)}")
        return np.loadtxt(source, delimiter=",", skiprows=1, ndmin=2).T
    except (OSError, ValueError) as e:
        raise PlotError(f"{source}: {e}") from e


def draw_sigma_curves(t, sdre, default, tuned):
    """σmax in units of 10⁶ (the curves sit near 3.26e6) and the relative differences in ppm, so
    that no axis needs an offset label."""
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=style.size(style.COLUMN, 1.0))
    for rank, (name, values) in enumerate(zip(CURVES, (sdre, default, tuned))):
        top.plot(t, 1e-6 * values, **style.line(name, CURVES, rank, samples=len(t)))
        if rank:
            bottom.plot(t, 1e6 * (values - sdre) / sdre, **style.line(name, CURVES, rank, samples=len(t)))
    top.ticklabel_format(axis="y", useOffset=False)
    bottom.axhline(0, color="black", linewidth=0.5)
    top.set_ylabel("σmax(P) (10⁶, –)")
    top.legend(loc="lower center", bbox_to_anchor=(0.5, 1.02), ncol=1, handlelength=3.2)
    bottom.set_ylabel("Δσ / σ_SDRE (ppm)")
    bottom.set_xlabel("time t (s)")
    fig.suptitle("σmax of the Riccati solution along an SDRE flight\nΔσ = σ_θD − σ_SDRE")
    return fig


def main(argv):
    """`plot_tuning.py SIGMA_CURVES_CSV OUT_STEM [--format png,pdf,svg]`; 0, or 1 after one line on stderr."""
    return style.figure_command(argv, "plot_tuning.py", __doc__, "sigma-curves.csv written by thetad tune",
                                read_curves, draw_sigma_curves)
