"""The figures of one flight flown by several controllers: the paper's eight kinds (Figs. 2–9 for
scenario I, 10–17 for scenario II) and three comparisons (tracking error, compute time, summary).

Each `draw_*` function returns a matplotlib Figure (tests inspect it); `draw_all` draws every one
and `main` saves them where a `thetad plot` manifest says (results.py describes it).
"""

import dataclasses
import math
import os
import sys
import textwrap
from dataclasses import dataclass

import numpy as np

from . import noise, paper, style
from .results import STEP_TIME, PlotError, load, read_manifest
from .style import plt

# A log at 1 kHz has 85 000 rows: lines are drawn from at most this many points (the noise band
# and the low-pass trend are computed at the full rate first).
POINTS = 2000


@dataclass(frozen=True)
class Signal:
    """A column to draw: schema name, axis label, sign (altitude is −z_p), the command column
    (then an error panel p − p_c follows) or whether a difference-to-baseline panel follows."""
    column: str
    label: str
    sign: float = 1.0
    reference: str = ""
    differences: bool = False


@dataclass(frozen=True)
class TimeFigure:
    kind: str
    title: str
    signals: tuple


TIME_FIGURES = (
    TimeFigure("position", "Position tracking",
               (Signal("x_p", "x", reference="x_c"), Signal("y_p", "y", reference="y_c"),
                Signal("z_p", "altitude h", sign=-1.0, reference="z_c"))),
    TimeFigure("euler_angles", "Euler angles",
               (Signal("phi", "roll φ", differences=True), Signal("theta", "pitch θ", differences=True),
                Signal("psi", "yaw ψ", differences=True))),
    TimeFigure("angular_rates", "Angular velocities", (Signal("p", "p"), Signal("q", "q"), Signal("r", "r"))),
    TimeFigure("body_velocities", "Translational (body) velocities",
               (Signal("u", "u"), Signal("v", "v"), Signal("w", "w"))),
    TimeFigure("flapping_angles", "Flapping angles",
               (Signal("a1", "a₁ (longitudinal)"), Signal("b1", "b₁ (lateral)"))),
    TimeFigure("control_deflections", "Commanded control deflections",
               (Signal("cmd_delta_ped", "δ_ped"), Signal("cmd_delta_col", "δ_col"),
                Signal("cmd_delta_lon", "δ_lon"), Signal("cmd_delta_lat", "δ_lat"))),
    TimeFigure("main_rotor_thrust", "Commanded main-rotor thrust", (Signal("cmd_T_mr", "T_mr"),)),
)
POSITION = ("x_p", "y_p", "z_p")
COMMAND = ("x_c", "y_c", "z_c")
NEEDED = sorted({"t", STEP_TIME, *POSITION, *COMMAND,
                 *(n for f in TIME_FIGURES for s in f.signals for n in (s.column, s.reference) if n)})
SETTINGS = {"paper": "paper setting: uncertainties, gust, 5 % noise", "ideal": "ideal: no uncertainty, gust or noise",
            "custom": "own disturbance settings"}
NUMERALS = {"scenario-1": "scenario I", "scenario-2": "scenario II"}


def thin(*arrays):
    """Every k-th sample of each array, at most POINTS of them."""
    step = max(1, len(arrays[0]) // POINTS)
    return [np.asarray(a)[::step] for a in arrays]


def title(figure, runs, kind, what):
    """Two lines: what and which flight; the paper's figure number where the paper has one."""
    flight = f"{NUMERALS.get(runs.scenario, runs.scenario)}, {SETTINGS[runs.setting]}, seed {runs.seed}"
    number = paper.figure_number(kind, runs.scenario)
    figure.suptitle(f"{what}{f' (cf. paper Fig. {number})' if number else ''}\n{flight}")


def columns(texts):
    """Legend columns that fill the rows evenly at column width; one for long (divergence) entries."""
    if max(len(text) for text in texts) > 30:
        return 1
    return 3 if len(texts) % 3 == 0 else 2


def run_texts(runs):
    """A legend text per run: its label; a run that did not complete also says how, when and why, wrapped to the
    column."""
    return [textwrap.fill(f"{run.label}: {run.ending()}", 55) if run.not_completed else run.label for run in runs.runs]


def entries(ax, runs, extra=()):
    """Legend handles and texts: one per run, then `extra`."""
    handles = [next(h for h in ax.get_lines() if h.get_label() == run.label) for run in runs.runs]
    return handles + [h for h, _ in extra], run_texts(runs) + [t for _, t in extra]


def legend(ax, runs, extra=()):
    """The legend above `ax`."""
    handles, texts = entries(ax, runs, extra)
    ax.legend(handles, texts, loc="lower center", bbox_to_anchor=(0.5, 1.02), ncol=columns(texts), borderaxespad=0,
              handlelength=3.2, columnspacing=1.2)


def mark_divergence(ax, run, t, y, look):
    """An × where the line of a run that did not complete ends."""
    if run.not_completed:
        ax.plot(t[-1:], y[-1:], marker="x", markersize=6, markeredgewidth=1.4, color=look["color"],
                linestyle="none", zorder=60, label="_not_completed")


def draw_signal(ax, runs, scale, column, noisy):
    """Every run's `column` times `scale`: the raw line, or for a noise-dominated signal the
    low-pass trend over the ±2 σ measured-noise band."""
    for rank, run in enumerate(runs.runs):
        t, y = run.data["t"].to_numpy(), scale * run.data[column].to_numpy()
        look = style.line(run.label, runs.labels, rank, samples=min(len(t), POINTS))
        if noisy:
            trend, sigma = noise.split(t, y)
            tt, lo, hi, y = thin(t, trend - 2 * sigma, trend + 2 * sigma, trend)
            ax.fill_between(tt, lo, hi, color=look["color"], alpha=0.18, linewidth=0, zorder=look["zorder"] - 5)
        else:
            tt, y = thin(t, y)
        ax.plot(tt, y, **look)
        mark_divergence(ax, run, tt, y, look)


def draw_error(ax, runs, signal, scale, unit):
    """Under a tracked signal: each run's error (signal − command), zero dotted."""
    for rank, run in enumerate(runs.runs):
        t, e = thin(run.data["t"], scale * (run.data[signal.column] - run.data[signal.reference]))
        ax.plot(t, e, **{**style.line(run.label, runs.labels, rank, samples=len(t)), "label": f"_{run.label}"})
    ax.axhline(0, color="black", linewidth=0.5, zorder=1)
    ax.set_ylabel(f"{signal.label.split()[-1]} − cmd ({unit})")


def draw_difference(ax, runs, signal, scale, unit):
    """Under an overlay without a command: each run's difference to the baseline run."""
    base = runs.base_run()
    tb, yb = base.data["t"].to_numpy(), base.data[signal.column].to_numpy()
    for rank, run in enumerate(runs.runs):
        if run is base:
            continue
        t = run.data["t"].to_numpy()
        inside = t <= tb[-1]
        d = scale * (run.data[signal.column].to_numpy()[inside] - np.interp(t[inside], tb, yb))
        t, d = thin(t[inside], d)
        ax.plot(t, d, **{**style.line(run.label, runs.labels, rank, samples=len(t)), "label": f"_{run.label}"})
    ax.axhline(0, color="black", linewidth=0.5, zorder=1)
    ax.set_ylabel(f"Δ{signal.label.split()[-1]} ({unit})")


def draw_time_figure(runs, figure):
    """One of the paper's time-history figures with every run overlaid; a tracked signal gets an
    error panel under it, an attitude a panel of differences to the baseline run."""
    rows = []
    for signal in figure.signals:
        rows.append((signal, "value"))
        if signal.reference:
            rows.append((signal, "error"))
        elif signal.differences and len(runs.runs) > 1:
            rows.append((signal, "difference"))
    heights = [2.0 if part == "value" else 1.0 for _, part in rows]
    # 1.1 in per value panel, half that per error panel, and room for the titles and the legend.
    fig, axes = plt.subplots(len(rows), 1, sharex=True, squeeze=False, gridspec_kw={"height_ratios": heights},
                             figsize=(style.COLUMN, 0.55 * sum(heights) + 1.0))
    axes = axes[:, 0]
    filtered = []
    for ax, (signal, part) in zip(axes, rows):
        unit, factor = runs.display(signal.column)
        scale = factor * signal.sign
        if part == "error":
            draw_error(ax, runs, signal, scale, unit)
        elif part == "difference":
            draw_difference(ax, runs, signal, scale, unit)
        else:
            noisy = any(noise.dominated(r.data["t"].to_numpy(), r.data[signal.column].to_numpy()) for r in runs.runs)
            draw_signal(ax, runs, scale, signal.column, noisy)
            if noisy:
                filtered.append(signal.label)
            if signal.reference:
                t, c = thin(runs.longest().data["t"], scale * runs.longest().data[signal.reference])
                ax.plot(t, c, **style.REFERENCE)
            ax.set_ylabel(f"{signal.label} ({unit})")
    axes[-1].set_xlabel("time t (s)")
    extra = [(axes[0].get_lines()[-1], "command")] if figure.signals[0].reference else []
    legend(axes[0], runs, extra)
    title(fig, runs, figure.kind, figure.title)
    notes = []
    if filtered:
        notes.append(f"{', '.join(filtered)}: noise-dominated; line: low-pass {noise.CUTOFF_HZ:g} Hz "
                     "(zero phase), band: ±2σ of the measured noise")
    if any(part == "difference" for _, part in rows):
        notes.append(f"Δ: difference to {runs.baseline}")
    if notes:
        fig.text(0.5, 0, textwrap.fill("; ".join(notes), 70), ha="center", va="top", fontsize=6.5)
    return fig


def equal_limits(ax, spans):
    """Axis limits with the same margin on all three axes and a box whose sides are the limits'
    spans: one metre is as long on x, y and h."""
    margin = 0.05 * max(hi - lo for lo, hi in spans)
    limits = [(lo - margin, hi + margin) for lo, hi in spans]
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_zlim(*limits[2])
    ax.set_box_aspect([hi - lo for lo, hi in limits], zoom=0.92)


def draw_trajectory_3d(runs):
    """The 3-D path of every run and the command, equal scales on all axes, seen from above the
    start corner so that the figure 8 / the circle is seen as a shape and the altitude still reads."""
    # Placed by hand: the layout engines do not see a 3-D axes' labels, and cut off the z label.
    # Below the plot, room for the legend's lines (0.14 in each); above, for the two title lines.
    texts = run_texts(runs) + ["command"]
    lines = sum(text.count("\n") + 1 for text in texts) / columns(texts)
    legend_height, plot_height, title_height = 0.14 * math.ceil(lines) + 0.1, 0.72 * style.COLUMN, 0.35
    height = legend_height + plot_height + title_height
    fig = plt.figure(figsize=(style.COLUMN, height), layout="none")
    ax = fig.add_axes((0.0, legend_height / height, 0.9, plot_height / height), projection="3d")
    command = runs.longest().data
    paths = [(r.data["x_p"], r.data["y_p"], -r.data["z_p"]) for r in runs.runs]
    paths.append((command["x_c"], command["y_c"], -command["z_c"]))
    spans = [(min(p[k].min() for p in paths), max(p[k].max() for p in paths)) for k in range(3)]
    for rank, (run, path) in enumerate(zip(runs.runs, paths)):
        x, y, h = thin(*path)
        look = style.line(run.label, runs.labels, rank, samples=len(x))
        ax.plot(x, y, h, **look)
        if run.not_completed:
            ax.plot(x[-1:], y[-1:], h[-1:], marker="x", markersize=6, color=look["color"], linestyle="none",
                    label="_not_completed")
    ax.plot(*thin(*paths[-1]), **style.REFERENCE)
    equal_limits(ax, spans)
    ax.view_init(elev=32, azim=-62)
    unit = runs.display("x_p")[0]
    ax.set_xlabel(f"x ({unit})", labelpad=-2)
    ax.set_ylabel(f"y ({unit})", labelpad=-2)
    ax.set_zlabel(f"h ({unit})", labelpad=-1)
    ax.tick_params(pad=-2)
    ax.zaxis.set_major_locator(plt.MaxNLocator(2, integer=True))
    handles, texts = entries(ax, runs, [(ax.get_lines()[-1], "command")])
    fig.legend(handles, texts, loc="lower center", ncol=columns(texts), handlelength=3.2, borderaxespad=0.2)
    title(fig, runs, "trajectory_3d", "3-D trajectory, equal scales")
    return fig


def draw_tracking_error(runs):
    fig, ax = plt.subplots(figsize=style.size(style.COLUMN, 0.62))
    for rank, run in enumerate(runs.runs):
        d = run.data
        error = np.sqrt(sum((d[p] - d[c]) ** 2 for p, c in zip(POSITION, COMMAND)))
        t, e = thin(d["t"], error)
        look = style.line(run.label, runs.labels, rank, samples=len(t))
        ax.plot(t, e, **look)
        mark_divergence(ax, run, t, e, look)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("‖p − p_c‖ (m)")
    legend(ax, runs)
    title(fig, runs, "tracking_error", "Position tracking error")
    return fig


def draw_compute_time(runs):
    """Median per window of the control() wall time in flight with its 5–95 % band, log axis, and
    the budget one controller period leaves."""
    unit, factor = runs.display(STEP_TIME)
    fig, ax = plt.subplots(figsize=style.size(style.COLUMN, 0.8))
    measured = [run for run in runs.runs if np.any(run.data[STEP_TIME] > 0)]
    for run in measured:
        rank = runs.labels.index(run.label)
        t, us = run.data["t"].to_numpy(), factor * run.data[STEP_TIME].to_numpy()
        width = max(1, len(us) // 400)
        count = len(us) // width
        windows = us[: count * width].reshape(count, width)
        tm = t[: count * width].reshape(count, width).mean(1)
        low, median, high = np.percentile(windows, [5, 50, 95], axis=1)
        look = style.line(run.label, runs.labels, rank, samples=len(tm))
        ax.fill_between(tm, np.maximum(low, 1e-3), high, color=look["color"], alpha=0.18, linewidth=0)
        ax.plot(tm, median, **look)
    if measured:
        period = float(runs.runs[0].summary["settings"]["controller_period_s"])
        budget = ax.axhline(period * 1e6, color="black", linewidth=0.9, linestyle=(0, (4, 2)))
        ax.set_yscale("log")
        legend(ax, dataclasses.replace(runs, runs=measured),
               [(budget, f"budget at {1e-3 / period:g} kHz ({period * 1e6:g} µs)")])
    else:
        ax.text(0.5, 0.5, "in-flight step time not measured in these runs", transform=ax.transAxes, ha="center")
    ax.set_xlabel("time t (s)")
    ax.set_ylabel(f"control() wall time ({unit})")
    ax.grid(True, which="minor", linewidth=0.2)
    title(fig, runs, "compute_time", "In-flight step time (median, 5–95 % band)")
    return fig


def draw_summary(runs):
    """Per controller, one row: RMS error per axis, cost J, in-flight median step time. Bars of runs
    that did not complete are hatched (their metrics stop where the run ended); the title says so
    only then."""
    labels = runs.labels
    looks = style.looks(labels)
    fig, axes = plt.subplots(1, 3, sharey=True, figsize=style.size(style.PAGE, 0.1 * len(labels) + 0.16))
    y = np.arange(len(labels))
    rms = np.array([[r.summary[f"rms_error_{axis}_m"] for axis in "xyz"] for r in runs.runs], dtype=float)
    for k, (axis, marker) in enumerate(zip(("x", "y", "h"), ("o", "s", "^"))):
        axes[0].plot(rms[:, k], y, marker=marker, linestyle="none", color="0.2", markerfacecolor="none",
                     markersize=5, label=axis)
    axes[0].set_xlabel("RMS position error (m)")
    axes[0].legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, handletextpad=0.1, borderaxespad=0.2)
    colours = [looks[label].colour for label in labels]
    hatches = ["////" if r.not_completed else None for r in runs.runs]
    cost = np.array([r.summary["cost"] for r in runs.runs], dtype=float)
    compute = np.array([r.summary.get("in_flight_step_time_median_us", 0.0) for r in runs.runs])
    for ax, values, xlabel in ((axes[1], cost, "cost J, Eq. 32 (–)"), (axes[2], compute, "in-flight median step time (µs)")):
        bars = ax.barh(y, values, color=colours, hatch=hatches, edgecolor="white", linewidth=0)
        ax.bar_label(bars, fmt="%.3g", padding=2, fontsize=6.5)
        positive = values[values > 0]
        if len(positive) and positive.max() / positive.min() > 30:
            ax.set_xscale("log")
        else:
            ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 3))
        ax.set_xlabel(xlabel)
        ax.margins(x=0.25)
    if compute.any():
        period = float(runs.runs[0].summary["settings"]["controller_period_s"])
        axes[2].axvline(period * 1e6, color="black", linewidth=0.9, linestyle=(0, (4, 2)))
        axes[2].text(period * 1e6, len(labels) - 0.55, f"budget at {1e-3 / period:g} kHz ", fontsize=6.5, ha="right",
                     va="bottom")
    axes[0].set_yticks(y, [f"{r.label}\n({r.status})" if r.not_completed else r.label for r in runs.runs])
    axes[0].invert_yaxis()
    for ax in axes:
        ax.grid(True, axis="x", which="both", linewidth=0.3)
        ax.grid(False, axis="y")
    endings = sorted({r.status for r in runs.runs if r.not_completed})
    what = "Summary" + (f" (hatched: {' or '.join(endings)}, metrics up to the end of the run)" if endings else "")
    title(fig, runs, "summary", what)
    return fig


def plant_figures(names):
    """A plant's own figures (docs/plants.md), from the log's column names: one panel per state (a
    column the log also has measured, meas_NAME) and one per commanded input (cmd_NAME)."""
    states = [name for name in names if f"meas_{name}" in names]
    inputs = [name for name in names if name.startswith("cmd_")]
    return (TimeFigure("states", "States", tuple(Signal(name, name) for name in states)),
            TimeFigure("inputs", "Commanded inputs", tuple(Signal(name, name[len("cmd_"):]) for name in inputs)))


def is_helicopter(manifest):
    """Whether the manifest's runs flew the helicopter (its log has the position x_p)."""
    return any(column["name"] == "x_p" for column in manifest["schema"])


def draw_all(runs, figures_of_plant=None):
    """{file stem: Figure} of every figure of a RunSet: the helicopter's, or with `figures_of_plant`
    (plant_figures) a plant's time histories and the compute time."""
    if figures_of_plant is not None:
        figures = {figure.kind: draw_time_figure(runs, figure) for figure in figures_of_plant}
        figures["compute_time"] = draw_compute_time(runs)
        return figures
    figures = {"trajectory_3d": draw_trajectory_3d(runs)}
    for figure in TIME_FIGURES:
        figures[figure.kind] = draw_time_figure(runs, figure)
    figures["tracking_error"] = draw_tracking_error(runs)
    figures["compute_time"] = draw_compute_time(runs)
    figures["summary"] = draw_summary(runs)
    return figures


def main(argv):
    """`plot_run.py MANIFEST`: every figure, saved where the manifest says; 0, or 1 after one line
    on stderr."""
    try:
        if len(argv) != 2:
            raise PlotError("usage: plot_run.py MANIFEST.json (written by `thetad plot`)")
        manifest = read_manifest(argv[1])
        style.apply()
        if is_helicopter(manifest):
            runs, figures = load(manifest, NEEDED), None
        else:
            figures = plant_figures([column["name"] for column in manifest["schema"]])
            runs = load(manifest, ["t", STEP_TIME, *(s.column for f in figures for s in f.signals)])
        for stem, fig in draw_all(runs, figures).items():
            style.save(fig, os.path.join(manifest["out"], stem), manifest["formats"], manifest["dpi"])
    except PlotError as e:
        print(f"plot_run.py: error: {e}", file=sys.stderr)
        return 1
    return 0
