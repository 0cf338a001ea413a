#!/usr/bin/python3
"""Draws the paper's figures (Xin, Xu & Hopkins 2011, Figs. 2-17) and three comparison figures
for every run in one thetad output directory, the controllers overlaid.

Not meant to be called by hand: `thetad plot --in DIR --out DIR` checks the runs, writes a
manifest (JSON) and calls this script with it as the only argument:

  {"title": "...", "out": "staging dir", "formats": ["png", "svg"], "dpi": 120,
   "schema": [{"name": "t", "unit": "s"}, ...],          # thetad::sim::log_schema(), in order
   "runs": [{"name": "theta-d", "csv": "...", "columns": ["t", ...], "summary": {...result JSON...}}, ...]}

The CSV columns are known only through "schema": thetad has already checked each CSV header
against it, and every column this script draws is looked up there by name, so a renamed column
is a clear error here and nowhere else is the column list written down. Needs Debian's
python3-matplotlib (run with /usr/bin/python3 and MPLBACKEND=Agg). Errors: one line on stderr
starting with "plot_run.py:", exit status 1.
"""

import json
import math
import os
import sys
import zlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

# One colour per controller name in every figure and every directory, so that figures of
# different scenarios can be read side by side. Other names get a stable colour from EXTRA.
COLOURS = {
    "theta-d": "#1f77b4",
    "sdre": "#ff7f0e",
    "lqr": "#2ca02c",
    "lqr-scheduled": "#d62728",
    "example-pid": "#9467bd",
}
EXTRA = ["#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"]
REFERENCE_STYLE = {"color": "black", "linestyle": "--", "linewidth": 1.0, "label": "command"}

# How a schema unit is shown to people (spec §8.2: degrees for angles): (label, factor).
DISPLAY_UNITS = {
    "s": ("s", 1.0),
    "m": ("m", 1.0),
    "m_per_s": ("m/s", 1.0),
    "rad": ("deg", 180.0 / math.pi),
    "rad_per_s": ("deg/s", 180.0 / math.pi),
    "N": ("N", 1.0),
    "ns": ("µs", 1e-3),
}

# Lines of 85 000 samples are drawn as this many windows (mean line, min-max band): the band is
# what the full line would cover, and the files stay small.
BUCKETS = 1500


class PlotError(Exception):
    pass


class Signal:
    """A column to draw: schema name, axis label, sign (altitude is -z_p) and the command column."""

    def __init__(self, column, label, sign=1.0, reference=None):
        self.column, self.label, self.sign, self.reference = column, label, sign, reference


# The paper's time-history figures (spec §8.2), scenario I / scenario II numbers.
TIME_FIGURES = [
    ("position", "position tracking (Figs. 3, 11)",
     [Signal("x_p", "x", reference="x_c"), Signal("y_p", "y", reference="y_c"),
      Signal("z_p", "altitude h = −z", sign=-1.0, reference="z_c")]),
    ("euler_angles", "Euler angles (Figs. 4, 12)",
     [Signal("phi", "roll φ"), Signal("theta", "pitch θ"), Signal("psi", "yaw ψ")]),
    ("angular_rates", "angular velocities (Figs. 5, 13)",
     [Signal("p", "p"), Signal("q", "q"), Signal("r", "r")]),
    ("body_velocities", "translational (body) velocities (Figs. 6, 14)",
     [Signal("u", "u"), Signal("v", "v"), Signal("w", "w")]),
    ("flapping_angles", "flapping angles (Figs. 7, 15)",
     [Signal("a1", "a₁ (longitudinal)"), Signal("b1", "b₁ (lateral)")]),
    ("control_deflections", "commanded control deflections (Figs. 8, 16)",
     [Signal("cmd_delta_ped", "δ_ped"), Signal("cmd_delta_col", "δ_col"),
      Signal("cmd_delta_lon", "δ_lon"), Signal("cmd_delta_lat", "δ_lat")]),
    ("main_rotor_thrust", "commanded main-rotor thrust (Figs. 9, 17)",
     [Signal("cmd_T_mr", "T_mr")]),
]
POSITION = ["x_p", "y_p", "z_p"]
COMMAND = ["x_c", "y_c", "z_c"]


def colour(name):
    if name in COLOURS:
        return COLOURS[name]
    return EXTRA[zlib.crc32(name.encode()) % len(EXTRA)]


def field(run, *path):
    value = run["summary"]
    for key in path:
        if not isinstance(value, dict) or key not in value:
            raise PlotError(f"{run['name']}: the summary JSON has no field {'.'.join(path)}")
        value = value[key]
    return value


def label(run):
    if field(run, "status") == "completed":
        return run["name"]
    return f"{run['name']} (diverged at {field(run, 'end_time_s'):.1f} s)"


class Schema:
    def __init__(self, columns):
        self.index = {c["name"]: i for i, c in enumerate(columns)}
        self.unit = {c["name"]: c["unit"] for c in columns}

    def require(self, names):
        missing = [n for n in names if n not in self.index]
        if missing:
            raise PlotError("the thetad log schema has no column " + ", ".join(missing) +
                            " (scripts/plot_run.py needs it: update the figure definitions)")

    def display(self, name):
        unit = self.unit[name]
        if unit not in DISPLAY_UNITS:
            raise PlotError(f"column {name}: unit '{unit}' has no display rule in scripts/plot_run.py")
        return DISPLAY_UNITS[unit]


def load(run, schema, names):
    """The run's columns `names` (SI units, as logged) as a dict of arrays. A run flown without
    timing has no compute column: it reads as zeros ("not measured")."""
    index = {name: i for i, name in enumerate(run["columns"])}
    present = [n for n in names if n in index]
    try:
        data = np.loadtxt(run["csv"], delimiter=",", skiprows=1, usecols=[index[n] for n in present], ndmin=2)
    except (OSError, ValueError) as e:
        raise PlotError(f"{run['csv']}: {e}") from e
    if data.shape[0] == 0:
        raise PlotError(f"{run['csv']}: no samples")
    columns = {n: data[:, k] for k, n in enumerate(present)}
    for n in names:
        if n not in index:
            if n != "compute":
                raise PlotError(f"{run['csv']}: no column {n}")
            columns[n] = np.zeros(data.shape[0])
    return columns


def windows(t, y, count):
    """About `count` consecutive windows of y (rows; the last padded with its final value) and
    each window's mean time."""
    width = max(1, len(y) // count)
    pad = -len(y) % width
    t = np.concatenate([t, np.full(pad, t[-1])]).reshape(-1, width)
    return t.mean(1), np.concatenate([y, np.full(pad, y[-1])]).reshape(-1, width)


def command_run(runs, data):
    """The data of the longest run: the command is the same for every run of a directory, and a
    diverged run logged only part of it."""
    return data[max(runs, key=lambda r: len(data[r["name"]]["t"]))["name"]]


def on_top(runs, run):
    """z-order that puts the first run of the directory (theta-d in a comparison) above the others."""
    return 2 + len(runs) - runs.index(run)


def band(ax, t, y, c, z):
    """y as its mean per window with the window's min-max range shaded: the 1 kHz noise shows as
    a band whose width is the noise, and the overlaid controllers' trends stay visible."""
    tm, w = windows(t, y, BUCKETS)
    if w.shape[1] > 1:
        ax.fill_between(tm, w.min(1), w.max(1), color=c, alpha=0.25, linewidth=0, zorder=z)
    ax.plot(tm, w.mean(1), color=c, linewidth=0.8, zorder=z)


def finish(fig, runs, title, name, settings, with_reference):
    handles = [plt.Line2D([], [], color=colour(r["name"]), label=label(r)) for r in runs]
    if with_reference:
        handles.append(plt.Line2D([], [], **REFERENCE_STYLE))
    fig.legend(handles=handles, loc="upper center", ncol=min(len(handles), 5), frameon=False,
               bbox_to_anchor=(0.5, 0.965))
    fig.suptitle(f"{settings['title']}: {title}", fontsize=10, y=0.995)
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    for fmt in settings["formats"]:
        fig.savefig(os.path.join(settings["out"], f"{name}.{fmt}"), dpi=settings["dpi"])
    plt.close(fig)


def time_figure(name, title, signals, runs, data, schema, settings):
    fig, axes = plt.subplots(len(signals), 1, sharex=True, figsize=(8, 1.9 * len(signals) + 1.2), squeeze=False)
    for ax, signal in zip(axes[:, 0], signals):
        unit, factor = schema.display(signal.column)
        scale = factor * signal.sign
        for run in runs:
            d = data[run["name"]]
            band(ax, d["t"], scale * d[signal.column], colour(run["name"]), on_top(runs, run))
        if signal.reference:
            d = command_run(runs, data)
            ax.plot(d["t"], scale * d[signal.reference], **{**REFERENCE_STYLE, "label": None}, zorder=len(runs) + 3)
        ax.set_ylabel(f"{signal.label} ({unit})")
        ax.grid(True, linewidth=0.3)
    axes[-1, 0].set_xlabel("time t (s)")
    finish(fig, runs, title, name, settings, with_reference=any(s.reference for s in signals))


def trajectory_3d(runs, data, schema, settings):
    fig = plt.figure(figsize=(8, 6.5))
    ax = fig.add_subplot(projection="3d")
    # Positions are smooth: every k-th sample keeps the shape and the files small.
    for run in runs:
        d = data[run["name"]]
        step = max(1, len(d["t"]) // 4000)
        ax.plot(d["x_p"][::step], d["y_p"][::step], -d["z_p"][::step], color=colour(run["name"]), linewidth=0.9,
                zorder=on_top(runs, run))
    d = command_run(runs, data)
    step = max(1, len(d["t"]) // 4000)
    ax.plot(d["x_c"][::step], d["y_c"][::step], -d["z_c"][::step], **{**REFERENCE_STYLE, "label": None})
    unit = schema.display("x_p")[0]
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    ax.set_zlabel(f"altitude h = −z ({unit})")
    spans = [max(np.ptp(d[c]), 1.0) for c in COMMAND]
    ax.set_box_aspect((spans[0], spans[1], max(spans[2], 0.5 * max(spans[:2]))), zoom=1.1)
    finish(fig, runs, "3-D trajectory (Figs. 2, 10)", "trajectory_3d", settings, with_reference=True)


def tracking_error(runs, data, settings):
    fig, ax = plt.subplots(figsize=(8, 3.6))
    for run in runs:
        d = data[run["name"]]
        error = np.sqrt(sum((d[p] - d[c]) ** 2 for p, c in zip(POSITION, COMMAND)))
        band(ax, d["t"], error, colour(run["name"]), on_top(runs, run))
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("‖p − p_c‖ (m)")
    ax.grid(True, linewidth=0.3)
    finish(fig, runs, "position tracking error norm", "tracking_error", settings, with_reference=False)


def compute_time(runs, data, schema, settings):
    unit, factor = schema.display("compute")
    fig, ax = plt.subplots(figsize=(8, 3.6))
    measured = False
    for run in runs:
        d = data[run["name"]]
        us = factor * d["compute"]
        if not np.any(us > 0):
            continue
        measured = True
        # Median per window with the 5-95 % band: single samples (page faults, preemption) would
        # otherwise hide the typical cost on a log axis.
        t, w = windows(d["t"], us, 500)
        low, median, high = np.percentile(w, [5, 50, 95], axis=1)
        c = colour(run["name"])
        ax.fill_between(t, np.maximum(low, 1e-3), high, color=c, alpha=0.2, linewidth=0)
        ax.plot(t, median, color=c, linewidth=0.9)
    if measured:
        ax.set_yscale("log")
    else:
        ax.text(0.5, 0.5, "compute time not measured in these runs", transform=ax.transAxes, ha="center")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel(f"control() wall time ({unit})")
    ax.set_title("line: median per window; band: 5–95 %", fontsize=8)
    ax.grid(True, which="both", linewidth=0.3)
    finish(fig, runs, "compute time per control step", "compute_time", settings, with_reference=False)


def hatch(run):
    return None if field(run, "status") == "completed" else "//"


def bars(ax, runs, values, ylabel, log):
    positions = np.arange(len(runs))
    drawn = ax.bar(positions, values, color=[colour(r["name"]) for r in runs], hatch=[hatch(r) for r in runs])
    ax.bar_label(drawn, fmt="%.3g", fontsize=7)
    ax.set_xticks(positions, [r["name"] for r in runs], rotation=30, ha="right")
    ax.set_ylabel(ylabel)
    if log and min(values) > 0 and max(values) / min(values) > 30:
        ax.set_yscale("log")
    ax.grid(True, axis="y", linewidth=0.3)


def summary(runs, settings):
    fig, axes = plt.subplots(1, 4, figsize=(11, 3.8))
    rms = np.array([field(r, "tracking_error_m", "rms") for r in runs], dtype=float)
    width = 0.8 / len(runs)
    for k, run in enumerate(runs):
        axes[0].bar(np.arange(3) + (k - (len(runs) - 1) / 2) * width, rms[k], width, color=colour(run["name"]),
                    hatch=hatch(run))
    axes[0].set_xticks(np.arange(3), ["x", "y", "z"])
    axes[0].set_ylabel("RMS position error (m)")
    axes[0].grid(True, axis="y", linewidth=0.3)
    bars(axes[1], runs, np.linalg.norm(rms, axis=1), "RMS error norm ‖rms(p − p_c)‖ (m)", log=True)
    bars(axes[2], runs, [field(r, "cost", "J") for r in runs], "cost J (Eq. 32)", log=True)
    bars(axes[3], runs, [1e-3 * r["summary"].get("compute_time_ns", {}).get("median", 0.0) for r in runs],
         "median compute time (µs)", log=True)
    finish(fig, runs, "summary (hatched: diverged, metrics up to divergence)", "summary", settings,
           with_reference=False)


def main(argv):
    if len(argv) != 2:
        raise PlotError("usage: plot_run.py MANIFEST.json (written by `thetad plot`)")
    try:
        with open(argv[1], encoding="utf-8") as f:
            settings = json.load(f)
    except (OSError, ValueError) as e:
        raise PlotError(f"cannot read the manifest {argv[1]}: {e}") from e
    schema = Schema(settings["schema"])
    runs = settings["runs"]
    if not runs:
        raise PlotError("the manifest lists no runs")
    needed = sorted({"t", "compute", *POSITION, *COMMAND,
                     *(n for _, _, signals in TIME_FIGURES for s in signals for n in (s.column, s.reference) if n)})
    schema.require(needed)
    data = {run["name"]: load(run, schema, needed) for run in runs}

    plt.rcParams.update({"font.size": 8, "svg.fonttype": "none"})
    trajectory_3d(runs, data, schema, settings)
    for name, title, signals in TIME_FIGURES:
        time_figure(name, title, signals, runs, data, schema, settings)
    tracking_error(runs, data, settings)
    compute_time(runs, data, schema, settings)
    summary(runs, settings)


if __name__ == "__main__":
    try:
        main(sys.argv)
    except PlotError as e:
        print(f"plot_run.py: error: {e}", file=sys.stderr)
        sys.exit(1)
