"""The figure of `thetad approximation` (docs/reproduction.md): along an SDRE flight, the relative
error of the θ–D series ΣT_i against the SDRE's P (Frobenius and σmax) and of the θ–D's control
against the SDRE's, on a log axis (the three span several decades), over time.
"""

import numpy as np

from . import style
from .results import PlotError
from .style import plt

COLUMNS = ["t_s", "frobenius_relative", "sigma_relative", "control_relative"]
CURVES = ["‖ΣT − P‖F / ‖P‖F", "|σmax(ΣT) − σmax(P)| / σmax(P)", "‖u_θD − u_SDRE‖R / ‖u_SDRE‖R"]


def read_errors(source):
    """(t, Frobenius, σmax, control) relative errors of an approximation.csv."""
    try:
        with open(source, encoding="utf-8") as f:
            header = f.readline().strip().split(",")
        if header[:len(COLUMNS)] != COLUMNS:
            raise PlotError(f"{source}: expected the columns {','.join(COLUMNS)}, ... first, got {','.join(header)}")
        return np.loadtxt(source, delimiter=",", skiprows=1, ndmin=2, usecols=range(len(COLUMNS))).T
    except (OSError, ValueError) as e:
        raise PlotError(f"{source}: {e}") from e


def draw_errors(t, frobenius, sigma, control):
    """One log-scaled panel; an exact zero (σmax errors can vanish) is left out of the log axis."""
    fig, ax = plt.subplots(figsize=style.size(style.COLUMN, 0.9))
    for rank, (name, values) in enumerate(zip(CURVES, (frobenius, sigma, control))):
        shown = np.where(values > 0, values, np.nan)
        ax.plot(t, shown, **style.line(name, CURVES, rank, samples=len(t)))
    ax.set_yscale("log")
    ax.set_ylabel("relative error (–)")
    ax.set_xlabel("time t (s)")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=1, handlelength=3.2)
    ax.set_title("θ–D against the SDRE along an SDRE flight")
    return fig


def main(argv):
    """`plot_approximation.py APPROXIMATION_CSV OUT_STEM [--format png,pdf,svg]`; 0, or 1 after one line on stderr."""
    return style.figure_command(argv, "plot_approximation.py", __doc__, "approximation.csv written by thetad approximation",
                                read_errors, draw_errors)
