"""Figures of a campaign report (matplotlib, Agg), drawn by campaign_report.py.

- CDFs of RMS position error and cost per controller (completed runs of every cell);
- completion rate per controller and cell with its Wilson 95 % interval;
- for a 2-D sweep, a heat map of completion per controller: the flight envelope;
- violins of the paired per-draw relative differences between controllers.

Every controller has the look it has in every thetad figure (scripts/thetad_plots/style.py).
"""

import itertools
import os

import matplotlib.pyplot as plt
import numpy as np

from thetad_plots import style

style.apply()


def save(figure, out, name):
    """Writes the PNG under a temporary name, then renames it: a reader never sees half a figure."""
    path = os.path.join(out, name)
    style.save(figure, path + ".partial", ["png"])
    os.replace(path + ".partial.png", path)
    return name


def cdf(runs, controllers, column, label, out, name):
    figure, axes = plt.subplots(figsize=style.size(style.COLUMN, 0.75))
    completed = runs[runs.status == "completed"]
    for controller in controllers:
        values = np.sort(completed[completed.controller == controller][column].to_numpy())
        if values.size:
            axes.step(values, np.arange(1, values.size + 1) / values.size, where="post",
                      **style.line(controller, controllers))
    axes.set_xlabel(label)
    axes.set_ylabel("fraction of completed runs")
    axes.set_xscale("log")
    axes.grid(True, which="both")
    axes.legend()
    return save(figure, out, name)


def completion(per_controller, controllers, out):
    cells = sorted({(r["cell"], r["cell_label"]) for r in per_controller})
    wide = len(cells) * len(controllers) > 8
    figure, axes = plt.subplots(figsize=style.size(style.PAGE if wide else style.COLUMN, 0.45 if wide else 0.75))
    width = 0.8 / len(controllers)
    looks = style.looks(controllers)
    for i, controller in enumerate(controllers):
        rows = [r for r in per_controller if r["controller"] == controller]
        x = np.array([r["cell"] for r in rows]) + (i - (len(controllers) - 1) / 2) * width
        rate = np.array([r["completion_rate"] for r in rows])
        # Clipped at 0: at 100 % the interval's upper end can fall an ulp below the rate.
        low = np.maximum(rate - np.array([r["completion_wilson95"][0] for r in rows]), 0.0)
        high = np.maximum(np.array([r["completion_wilson95"][1] for r in rows]) - rate, 0.0)
        axes.errorbar(x, 100 * rate, yerr=100 * np.vstack([low, high]), fmt=looks[controller].marker, capsize=2,
                      markersize=3.5, label=controller, color=looks[controller].colour)
    axes.set_xticks([c for c, _ in cells])
    axes.set_xticklabels([label for _, label in cells], rotation=60, ha="right", fontsize=6)
    axes.set_ylabel("completed runs [%] (Wilson 95 %)")
    axes.set_ylim(-5, 105)
    axes.grid(True, axis="y")
    axes.legend()
    return save(figure, out, "completion.png")


def envelope(per_controller, controllers, swept, out):
    names = []
    x_name, y_name = swept
    for controller in controllers:
        rows = [r for r in per_controller if r["controller"] == controller]
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
        axes.set_xticks(range(len(xs)), [f"{v:g}" for v in xs])
        axes.set_yticks(range(len(ys)), [f"{v:g}" for v in ys])
        axes.set_xlabel(x_name)
        axes.set_ylabel(y_name)
        axes.set_title(f"{controller}: completed runs [%]")
        figure.colorbar(image, ax=axes)
        names.append(save(figure, out, f"envelope_{controller}.png"))
    return names


def violins(runs, controllers, out):
    completed = runs[runs.status == "completed"]
    data, labels = [], []
    for a, b in itertools.combinations(controllers, 2):
        left = completed[completed.controller == a].set_index(["cell", "scenario", "draw"])
        right = completed[completed.controller == b].set_index(["cell", "scenario", "draw"])
        both = left.join(right, how="inner", lsuffix="_a", rsuffix="_b")
        for column in ("rms_error_m", "cost"):
            ratios = (both[column + "_a"] / both[column + "_b"] - 1.0).to_numpy() * 100
            if ratios.size >= 2:
                data.append(ratios)
                labels.append(f"{a} vs {b}\n{column}")
    if not data:
        return []
    figure, axes = plt.subplots(figsize=style.size(style.PAGE if len(data) > 4 else style.COLUMN, 0.45 if len(data) > 4 else 0.75))
    axes.violinplot(data, showmedians=True)
    axes.axhline(0.0, color="black", linewidth=0.8)
    axes.set_xticks(range(1, len(data) + 1), labels, fontsize=6)
    axes.set_ylabel("paired difference a/b - 1 [%]")
    axes.grid(True, axis="y")
    return [save(figure, out, "paired_violins.png")]


def draw_figures(runs, per_controller, controllers, swept, out):
    """Draws every figure into `out`; returns their file names."""
    names = [cdf(runs, controllers, "rms_error_m", "RMS position error [m]", out, "cdf_rms_error.png"),
             cdf(runs, controllers, "cost", "cost J", out, "cdf_cost.png"),
             completion(per_controller, controllers, out)]
    if len(swept) == 2:
        names += envelope(per_controller, controllers, swept, out)
    names += violins(runs, controllers, out)
    return names
