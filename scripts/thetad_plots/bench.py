"""The benchmark figures of docs/performance.md, from the Google Benchmark JSON that bench/report.py
reads: the cost of one control step per controller, and its growth with the state dimension.

    draw_step_costs({row: [µs per repetition]}, budget_us)  -> Figure
    draw_scaling({kind: [(n, median, p10, p90)]}, labels)    -> Figure
    fit_power_law(ns, times)                                 -> PowerLaw (exponent, R², holds)
"""

import math
from dataclasses import dataclass

import numpy as np
from matplotlib.ticker import LogLocator, LogFormatterSciNotation, NullFormatter

from . import style
from .style import plt

# A power law t = c nᵖ is claimed only where it describes the data: at least MIN_SIZES sizes and a
# straight line in log t against log n that explains at least MIN_R2 of the variance. A cost flat
# in n (overhead-dominated, like LQR's) or bending (leaving a cache) fails it and gets no slope.
MIN_SIZES = 4
MIN_R2 = 0.99


@dataclass(frozen=True)
class PowerLaw:
    exponent: float
    r2: float
    sizes: int

    @property
    def holds(self):
        return self.sizes >= MIN_SIZES and self.r2 >= MIN_R2


def fit_power_law(ns, times):
    """The least-squares fit of log t = log c + p log n (`holds` says whether to believe it)."""
    x, y = np.log(np.asarray(ns, dtype=float)), np.log(np.asarray(times, dtype=float))
    if len(x) < 2:
        return PowerLaw(float("nan"), 0.0, len(x))
    slope, intercept = np.polyfit(x, y, 1)
    total = np.sum((y - y.mean()) ** 2)
    r2 = 1.0 - np.sum((y - (slope * x + intercept)) ** 2) / total if total > 0 else 0.0
    return PowerLaw(float(slope), float(r2), len(x))


def controller_of(row):
    """The controller a benchmark row measures: 'sdre-warm/passes:3' -> 'sdre', 'theta-d/…' -> 'theta-d'."""
    name = row.split("/")[0]
    return "sdre" if name.startswith("sdre") else name


def draw_step_costs(times, budget_us):
    """A box per benchmark row of its per-repetition CPU times (log axis), coloured by controller,
    with the budget of one control period marked."""
    rows = [row for row, values in times.items() if values]
    controllers = list(dict.fromkeys(controller_of(row) for row in rows))
    looks = style.looks(controllers)
    fig, ax = plt.subplots(figsize=style.size(style.COLUMN, 0.055 * len(rows) + 0.35))
    y = np.arange(len(rows))
    boxes = ax.boxplot([times[row] for row in rows], positions=y, vert=False, widths=0.6, patch_artist=True,
                       showfliers=True, flierprops={"markersize": 2}, medianprops={"color": "black"})
    for box, row, position in zip(boxes["boxes"], rows, y):
        look = looks[controller_of(row)]
        box.set(facecolor=look.colour, alpha=0.8, linewidth=0.6)
        # The repetitions often agree to a few per cent, a box too thin to show its colour: the
        # median's marker in the controller's look names it.
        ax.plot([np.median(times[row])], [position], marker=look.marker, color=look.colour, markersize=4,
                markeredgecolor="black", markeredgewidth=0.4, linestyle="none", zorder=5)
    ax.axvline(budget_us, color="black", linewidth=0.9, linestyle=(0, (4, 2)))
    ax.text(budget_us, -0.9, f"budget at {1e3 / budget_us:g} kHz ", ha="right", va="bottom", fontsize=6.5)
    ax.set_yticks(y, rows, fontsize=6.5)
    ax.set_ylim(len(rows) - 0.5, -1.2)
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(base=10))
    ax.xaxis.set_minor_locator(LogLocator(base=10, subs=np.arange(2, 10)))
    ax.set_xlabel("CPU time per control step (µs)")
    ax.grid(True, axis="x", which="both", linewidth=0.3)
    ax.grid(False, axis="y")
    fig.suptitle("One control step, helicopter (n = 18, m = 5)\nbox: repetitions' quartiles, whiskers 1.5 IQR")
    return fig


def log_axis(axis, values):
    """Decade ticks labelled, and where the data span less than two decades, 2 and 5 as well."""
    values = [v for v in values if v > 0]
    decades = math.log10(max(values) / min(values)) if values else 0
    subs = (1.0, 2.0, 5.0) if decades < 2 else (1.0,)
    axis.set_major_locator(LogLocator(base=10, subs=subs))
    axis.set_major_formatter(LogFormatterSciNotation(labelOnlyBase=False) if decades >= 2 else
                             plt.FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_locator(LogLocator(base=10, subs=np.arange(2, 10)))
    axis.set_minor_formatter(NullFormatter())


def draw_scaling(series, labels):
    """Median per-step time against n on log–log axes (bars p10–p90); a fitted line and its
    printed slope only where the fit holds."""
    kinds = list(series)
    looks = style.looks(kinds)
    fig, ax = plt.subplots(figsize=style.size(style.COLUMN, 0.8))
    ns_all, times_all = [], []
    for kind in kinds:
        points = sorted(series[kind])
        ns, med = [p[0] for p in points], [p[1] for p in points]
        look = looks[kind]
        fit = fit_power_law(ns, med)
        text = labels.get(kind, kind) + (f": slope {fit.exponent:.2f} (R² {fit.r2:.3f})" if fit.holds else
                                         f": no power law (R² {fit.r2:.2f})")
        ax.errorbar(ns, med, yerr=[[p[1] - p[2] for p in points], [p[3] - p[1] for p in points]], color=look.colour,
                    marker=look.marker, markersize=4, linestyle="none", capsize=2, label=text)
        if fit.holds:
            x = np.array([min(ns), max(ns)], dtype=float)
            c = np.exp(np.mean(np.log(med)) - fit.exponent * np.mean(np.log(ns)))
            ax.plot(x, c * x ** fit.exponent, color=look.colour, linestyle=look.dashes, linewidth=1.0)
        else:
            ax.plot(ns, med, color=look.colour, linestyle=look.dashes, linewidth=0.6, alpha=0.6)
        ns_all += ns
        times_all += med
    ax.set_xscale("log")
    ax.set_yscale("log")
    log_axis(ax.xaxis, ns_all)
    log_axis(ax.yaxis, times_all)
    ax.set_xticks(sorted(set(ns_all)), [str(n) for n in sorted(set(ns_all))])
    ax.set_xlabel("state dimension n (m = n/3)")
    ax.set_ylabel("CPU time per step (µs, median)")
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=1, fontsize=6.5)
    fig.suptitle(f"Per-step cost against n (synthetic SDC plants)\nline: power-law fit where R² ≥ {MIN_R2} "
                 f"over ≥ {MIN_SIZES} sizes")
    return fig
