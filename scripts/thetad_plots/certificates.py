"""The certificates figure (docs/reproduction.md, docs/model.md §8.4): along flights flown with
`certificates: on`, the SDRE's CARE condition estimate and stabilizability margin and θ–D's
last-term share of u, over time, one column of panels per flight; the share on a log axis (it
spans decades), the SDRE's two on linear ones (they move by tens of per cent). A dotted line marks
the time of the run's worst value (the result JSON's), a solid one where a run ended early.

Each flight is a result folder of `thetad compare` (or `thetad run`) holding an `sdre` and a
`theta-d` run; a column is given as TITLE=FOLDER. The certificate columns are found through each
result JSON's `log.columns`, so only the runs that logged them are drawn.
"""

import argparse
import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from . import style
from .results import PlotError
from .style import plt

# (log column, controller label, axis label, y scale)
PANELS = [
    ("condition_estimate", "sdre", "SDRE: CARE condition", "linear"),
    ("stabilizability_margin", "sdre", "SDRE: stabilizability\nmargin", "linear"),
    ("last_term_ratio", "theta-d", "θ–D: ‖u_last‖R / ‖u‖R", "log"),
]


def read_run(folder, label):
    """(the result JSON, the log as a DataFrame by column name) of run `label` in `folder`."""
    result_file = Path(folder) / f"{label}.json"
    try:
        result = json.loads(result_file.read_text(encoding="utf-8"))
        log = result.get("log")
        if not log:
            raise PlotError(f"{result_file}: the run has no log (flown --summary-only)")
        names = [column["name"] for column in log["columns"]]
        data = pd.read_csv(Path(folder) / log["csv"], header=0, names=names, dtype=float)
    except (OSError, ValueError, KeyError) as e:
        raise PlotError(f"{result_file}: {e}") from e
    return result, data


def read_flights(pairs):
    """[(title, {label: (result, data)})] of TITLE=FOLDER pairs."""
    flights = []
    for pair in pairs:
        title, sep, folder = pair.partition("=")
        if not sep:
            raise PlotError(f"{pair}: expected TITLE=FOLDER")
        flights.append((title, {label: read_run(folder, label) for label in {label for _, label, _, _ in PANELS}}))
    return flights


def draw(flights):
    """One row per certificate, one column per flight; a run that ended early says when."""
    fig, axes = plt.subplots(len(PANELS), len(flights), figsize=style.size(style.PAGE, 0.75), sharex="col",
                             squeeze=False)
    for col, (title, runs) in enumerate(flights):
        for row, (column, label, name, scale) in enumerate(PANELS):
            ax = axes[row][col]
            result, data = runs[label]
            if column not in data:
                raise PlotError(f"run {label} of '{title}' has no column {column} (fly it with certificates: on)")
            values = data[column].to_numpy()
            # An exact zero (θ–D's later terms are switched off at t0, Eq. 25) is left off a log axis.
            shown = np.where(values > 0, values, np.nan) if scale == "log" else values
            ax.plot(data["t"].to_numpy(), shown, **{**style.line(label, [label]), "linewidth": 0.8})
            ax.set_yscale(scale)
            worst = result.get("certificates", {}).get(column)
            if worst and worst.get("t_s") is not None:
                ax.axvline(worst["t_s"], color="black", linewidth=0.6, linestyle=(0, (2, 2)))
            if result.get("status") != "completed":
                ax.axvline(result["end_time_s"], color="black", linewidth=0.9)
            if col == 0:
                ax.set_ylabel(name)
            if row == 0:
                ax.set_title(title)
        axes[-1][col].set_xlabel("time t (s)")
    return fig


def main(argv):
    """`plot_certificates.py OUT_STEM TITLE=FOLDER ... [--format png,pdf,svg]`; 0, or 1 after one line on stderr."""
    parser = argparse.ArgumentParser(prog="plot_certificates.py", description=__doc__)
    parser.add_argument("out", help="output path without extension")
    parser.add_argument("flights", nargs="+", help="TITLE=FOLDER: a result folder with sdre and theta-d runs")
    style.add_format_option(parser)
    arguments = parser.parse_args(argv[1:])
    try:
        style.apply()
        style.save(draw(read_flights(arguments.flights)), arguments.out, arguments.formats, dpi=150)
    except (PlotError, ValueError) as e:
        print(f"plot_certificates.py: error: {e}", file=sys.stderr)
        return 1
    return 0
