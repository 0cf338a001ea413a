"""Figures of a campaign report (matplotlib, Agg), drawn by campaign_report.py.

- CDFs of the RMS 3-D position error, J_dev and J per controller (completed runs of every cell);
- completion rate per controller and cell with its Wilson 95 % interval;
- for a 2-D sweep, a heat map of completion per controller: the flight envelope;
- violins of the paired per-draw relative differences of each controller against the first.

Every controller has the look it has in every thetad figure (scripts/thetad_plots/style.py).
"""

import itertools
import os

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import ticker

from thetad_plots import style

style.apply()


# Above this many controllers a legend goes beside the axes, where it hides no data.
LEGEND_INSIDE = 4
# The paired figures' columns and their names on the axes.
PAIRED_FIGURES = (("rms_error_m", "RMS 3-D error"), ("cost_dev", "J_dev"), ("cost", "J"))


def legend(axes, count):
    if count <= LEGEND_INSIDE:
        axes.legend(loc="best")
    else:
        axes.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=5, ncol=1 + count // 16, borderaxespad=0)


def plain_log_labels(axis):
    """Tick labels a reader can take in on a log axis: plain numbers at the decades and at 2 and 5
    times them (10⁻¹ alone says little over a decade or less)."""
    axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))

    def minor(value, _):
        mantissa = value / 10 ** np.floor(np.log10(value))
        return f"{value:g}" if round(mantissa) in (2, 5) and abs(mantissa - round(mantissa)) < 1e-6 else ""
    axis.set_minor_formatter(ticker.FuncFormatter(minor))
    axis.set_tick_params(which="minor", labelsize=5)


def save(figure, out, name):
    """Writes the PNG under a temporary name, then renames it: a reader never sees half a figure."""
    path = os.path.join(out, name)
    style.save(figure, path + ".partial", ["png"])
    os.replace(path + ".partial.png", path)
    return name


def cdf(runs, controllers, column, label, out, name):
    many = len(controllers) > LEGEND_INSIDE  # the legend beside the axes needs the page's width
    figure, axes = plt.subplots(figsize=style.size(style.PAGE if many else style.COLUMN, 0.45 if many else 0.75))
    completed = runs[runs.status == "completed"]
    for controller in controllers:
        values = np.sort(completed[completed.label == controller][column].to_numpy())
        if values.size:
            axes.step(values, np.arange(1, values.size + 1) / values.size, where="post",
                      **style.line(controller, controllers))
    axes.set_xlabel(label)
    axes.set_ylabel("fraction of completed runs")
    axes.set_xscale("log")
    plain_log_labels(axes.xaxis)
    axes.grid(True, which="both")
    legend(axes, len(controllers))
    return save(figure, out, name)


def completion(per_controller, controllers, out):
    """Completion with its Wilson interval: per controller along the axis for one cell, else per
    cell with the controllers side by side."""
    cells = sorted({(r["cell"], r["cell_label"]) for r in per_controller})
    looks = style.looks(controllers)
    wide = len(cells) * len(controllers) > 8
    figure, axes = plt.subplots(figsize=style.size(style.PAGE if wide else style.COLUMN, 0.45 if wide else 0.75))
    single = len(cells) == 1
    width = 0.8 / len(controllers)
    for i, controller in enumerate(controllers):
        rows = [r for r in per_controller if r["label"] == controller]
        x = np.full(len(rows), float(i)) if single else \
            np.array([r["cell"] for r in rows]) + (i - (len(controllers) - 1) / 2) * width
        rate = np.array([r["completion_rate"] for r in rows])
        # Clipped at 0: at 100 % the interval's upper end can fall an ulp below the rate.
        low = np.maximum(rate - np.array([r["completion_ci95"][0] for r in rows]), 0.0)
        high = np.maximum(np.array([r["completion_ci95"][1] for r in rows]) - rate, 0.0)
        axes.errorbar(x, 100 * rate, yerr=100 * np.vstack([low, high]), fmt=looks[controller].marker, capsize=2,
                      markersize=3.5, label=controller, color=looks[controller].colour)
    if single:
        axes.set_xticks(range(len(controllers)), controllers, rotation=60, ha="right", fontsize=6)
        axes.set_title(cells[0][1], fontsize=7)
    else:
        axes.set_xticks([c for c, _ in cells], [label for _, label in cells], rotation=60, ha="right", fontsize=6)
        legend(axes, len(controllers))
    axes.set_ylabel("completed [%]\n(Wilson 95 %)")
    axes.set_ylim(-5, 105)
    axes.grid(True, axis="y")
    return save(figure, out, "completion.png")


def tick_label(value):
    """A factor's value, or a scenario's name: with several scenarios the report makes the scenario a
    factor of its own (campaign_report.by_scenario), so one swept factor gives a 2-D envelope."""
    return value if isinstance(value, str) else f"{value:g}"


def envelope(per_controller, controllers, swept, out):
    names = []
    x_name, y_name = swept
    for controller in controllers:
        rows = [r for r in per_controller if r["label"] == controller]
        xs = sorted({r["factors"][x_name] for r in rows})
        ys = sorted({r["factors"][y_name] for r in rows})
        grid = np.full((len(ys), len(xs)), np.nan)
        for r in rows:
            grid[ys.index(r["factors"][y_name]), xs.index(r["factors"][x_name])] = 100 * r["completion_rate"]
        figure, axes = plt.subplots(figsize=style.size(style.COLUMN, 0.8))
        image = axes.imshow(grid, origin="lower", cmap="viridis", vmin=0, vmax=100, aspect="auto")
        for (row, col), value in np.ndenumerate(grid):
            if np.isfinite(value):
                axes.text(col, row, f"{value:.0f}", ha="center", va="center", fontsize=6,
                          color="white" if value < 60 else "black")
        axes.set_xticks(range(len(xs)), [tick_label(v) for v in xs])
        axes.set_yticks(range(len(ys)), [tick_label(v) for v in ys])
        axes.set_xlabel(x_name)
        axes.set_ylabel(y_name)
        axes.set_title(f"{controller}: completed runs [%]")
        figure.colorbar(image, ax=axes)
        names.append(save(figure, out, f"envelope_{controller}.png"))
    return names


def violins(runs, controllers, out):
    """The per-draw relative differences of every controller against the first (the baseline of
    the campaign file), one row each, one panel per figure: all pairs are in report.json."""
    completed = runs[runs.status == "completed"]
    baseline = controllers[0]
    right = completed[completed.label == baseline].set_index(["cell", "scenario", "draw"])
    panels = []
    for column, name in PAIRED_FIGURES:
        data, labels = [], []
        for a in controllers[1:]:
            left = completed[completed.label == a].set_index(["cell", "scenario", "draw"])
            both = left.join(right, how="inner", lsuffix="_a", rsuffix="_b")
            ratios = (both[column + "_a"] / both[column + "_b"] - 1.0).to_numpy() * 100
            ratios = ratios[np.isfinite(ratios)]
            if ratios.size >= 2:
                data.append(ratios)
                labels.append(a)
        if data:
            panels.append((name, data, labels))
    if not panels:
        return []
    rows = max(len(labels) for _, _, labels in panels)
    figure, axes = plt.subplots(1, len(panels), sharey=True, squeeze=False,
                                figsize=style.size(style.PAGE, min(1.2, 0.12 + 0.035 * rows)))
    for axis, (name, data, labels) in zip(axes[0], panels):
        axis.violinplot(data, vert=False, showmedians=True)
        axis.axvline(0.0, color="black", linewidth=0.8)
        axis.set_yticks(range(1, len(labels) + 1), labels, fontsize=6)
        axis.set_title(name, fontsize=7)
        axis.grid(True, axis="x")
    axes[0][0].invert_yaxis()
    figure.supxlabel(f"paired difference a / {baseline} - 1 [%]", fontsize=7)
    return [save(figure, out, "paired_violins.png")]


def draw_figures(runs, per_controller, controllers, swept, out):
    """Draws every figure into `out`; returns their file names."""
    names = [cdf(runs, controllers, "rms_error_m", "RMS 3-D position error [m]", out, "cdf_rms_error.png"),
             cdf(runs, controllers, "cost_dev", "J_dev (deviations from the trim)", out, "cdf_cost_dev.png"),
             cdf(runs, controllers, "cost", "cost J", out, "cdf_cost.png"),
             completion(per_controller, controllers, out)]
    if len(swept) == 2:
        names += envelope(per_controller, controllers, swept, out)
    names += violins(runs, controllers, out)
    return names
