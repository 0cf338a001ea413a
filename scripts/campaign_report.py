#!/usr/bin/env python3
"""thetad campaign report: the statistics of a campaign database as a Markdown table, a JSON file
and figures (docs/campaigns.md). Run by `thetad campaign report DIR` under Debian's Python:

    /usr/bin/python3 campaign_report.py DIR/campaign.sqlite OUT [--seed N] [--resamples N]

Per controller (label) and sweep cell: completion rate with its Wilson 95 % interval; mean, median,
p90, p99 and max of each metric over the completed runs (a run that did not complete has figures
only up to its end); the reasons runs did not complete, tallied; and paired relative differences
between controllers over the draws both completed, with seeded bootstrap intervals
(campaign_stats.py). Names as docs/glossary.md gives them (Campaign report statistics).
"""

import argparse
import itertools
import json
import os
import sqlite3
import sys

import pandas as pd

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import campaign_stats  # noqa: E402
import plot_campaign  # noqa: E402

FORMAT = "thetad-campaign-1"
# The versions this report reads: 2 added J_dev (cost_dev) and the information set of each run, 3 the
# factors course and actuator_limits, 4 turbulence_model, turbulence_intensity, turbulence_scale,
# servo_delay and servo_time_constant (columns it reads only when they were swept), 5 docs/glossary.md's
# names (OLD_NAMES, and the registered name in column controller), 6 the factor slowdown and the flight
# computer's missed_deadlines, longest_missed_run and skipped_samples, 7 a column for each member of a
# factor family the campaign names (plant.epsilon, initial_state.0).
FORMAT_VERSIONS = ("2", "3", "4", "5", "6", "7")
# The columns of versions 2 to 4 that version 5 renamed, to their docs/glossary.md names.
OLD_NAMES = {
    "controller": "label",
    "rms_x_m": "rms_error_x_m", "rms_y_m": "rms_error_y_m", "rms_z_m": "rms_error_z_m",
    "max_x_m": "max_error_x_m", "max_y_m": "max_error_y_m", "max_z_m": "max_error_z_m",
    "max_error_m": "max_axis_error_m",
    "effort_thrust_N": "rms_command_T_mr_N", "effort_pedal_rad": "rms_command_delta_ped_rad",
    "effort_collective_rad": "rms_command_delta_col_rad", "effort_longitudinal_rad": "rms_command_delta_lon_rad",
    "effort_lateral_rad": "rms_command_delta_lat_rad",
    "compute_us_mean": "in_flight_step_time_mean_us", "compute_us_median": "in_flight_step_time_median_us",
    "compute_us_p99": "in_flight_step_time_p99_us", "wall_s": "wall_time_s",
    "duration": "duration_s", "dt": "dt_s", "gust_onset": "gust_onset_s",
    "initial_offset_x": "initial_offset_x_m", "initial_offset_y": "initial_offset_y_m",
    "initial_offset_z": "initial_offset_z_m", "initial_offset_roll": "initial_offset_roll_deg",
    "initial_offset_pitch": "initial_offset_pitch_deg", "initial_offset_yaw": "initial_offset_yaw_deg",
    "servo_delay": "servo_delay_samples", "servo_time_constant": "servo_time_constant_s",
}
# report.json's format_version: 2 renamed the keys to docs/glossary.md's (controller -> label,
# figures -> metrics, completion_wilson95 -> completion_ci95, divergence_reasons ->
# not_completed_reasons; paired: figure -> metric, median -> relative_difference_median, low/high ->
# relative_difference_ci95); 1 had no format_version.
REPORT_FORMAT_VERSION = 2
# The metrics summarized per label and cell: column, what it is, unit.
METRICS = [
    ("rms_error_m", "RMS 3-D position error", "m"),
    ("max_axis_error_m", "max per-axis position error", "m"),
    ("cost_dev", "J_dev (deviations from the trim)", ""),
    ("cost", "cost J", ""),
    ("rms_command_T_mr_N", "RMS thrust command", "N"),
    ("in_flight_step_time_mean_us", "in-flight step time, mean", "us"),
]
# The metrics compared in pairs (timing is not: it is not paired by the draw).
PAIRED = ["rms_error_m", "max_axis_error_m", "cost_dev", "cost"]


# Below this many paired draws a percentile bootstrap interval is too rough to lean on: said beside it.
SMALL_SAMPLE = 10


class ReportError(Exception):
    """What stops a report: the message names the database and the reason."""


def read_campaign(database):
    with sqlite3.connect(f"file:{database}?mode=ro", uri=True) as connection:
        meta = dict(connection.execute("SELECT key, value FROM meta").fetchall())
        if meta.get("format") != FORMAT:
            raise ReportError(f"{database}: not a thetad campaign database ({FORMAT})")
        version = meta.get("format_version", "1")
        if version.isdigit() and int(version) > int(FORMAT_VERSIONS[-1]):
            raise ReportError(f"{database}: written by a newer thetad (format_version {version}; this report reads "
                              f"up to {FORMAT_VERSIONS[-1]})")
        if version not in FORMAT_VERSIONS:
            raise ReportError(f"{database}: a campaign database of format_version {version}, written by another "
                              f"thetad; this report reads versions {', '.join(FORMAT_VERSIONS)}: run the campaign anew")
        runs = pd.read_sql("SELECT * FROM runs ORDER BY run_index", connection)
    if int(version) < 5:
        runs = runs.rename(columns=OLD_NAMES)
        meta["labels"] = meta.pop("controllers")
        meta["swept"] = json.dumps([OLD_NAMES.get(name, name) for name in json.loads(meta["swept"])])
    return meta, runs


def factor_value(value):
    return value if isinstance(value, str) else float(value)


def cell_label(row, swept):
    if not swept:
        return "all runs"
    return ", ".join(f"{name}={row[name]}" if isinstance(row[name], str) else f"{name}={row[name]:g}"
                     for name in swept)


def by_scenario(runs, swept):
    """With several scenarios, each (cell, scenario) is reported as a cell of its own, the scenario
    its last factor: a figure of one scenario is not pooled with another's."""
    if runs.scenario.nunique() < 2:
        return runs, swept
    runs = runs.copy()
    runs["cell"] = runs.groupby(["cell", "scenario"], sort=True).ngroup()
    return runs, swept + ["scenario"]


def controller_rows(runs, labels, swept):
    rows = []
    for (cell, label), group in runs.groupby(["cell", "label"], sort=False):
        completed = group[group.status == "completed"]
        low, high = campaign_stats.wilson_interval(len(completed), len(group))
        reasons = group[group.status != "completed"].reason.map(campaign_stats.reason_kind).value_counts()
        rows.append({
            "cell": int(cell),
            "cell_label": cell_label(group.iloc[0], swept),
            "factors": {name: factor_value(group.iloc[0][name]) for name in swept},
            "label": label,
            "information": ", ".join(sorted(set(group.information))),
            "runs": int(len(group)),
            "completed": int(len(completed)),
            "completion_rate": len(completed) / len(group),
            "completion_ci95": [low, high],
            "metrics": {column: campaign_stats.summary(completed[column]) for column, _, _ in METRICS},
            "not_completed_reasons": {str(k): int(v) for k, v in reasons.items()},
        })
    order = {label: i for i, label in enumerate(labels)}
    return sorted(rows, key=lambda r: (r["cell"], order[r["label"]]))


def paired_rows(runs, labels, swept, seed, resamples):
    rows = []
    for cell, group in runs.groupby("cell", sort=True):
        completed = group[group.status == "completed"]
        for (i, a), (j, b) in itertools.combinations(enumerate(labels), 2):
            left = completed[completed.label == a].set_index(["scenario", "draw"])
            right = completed[completed.label == b].set_index(["scenario", "draw"])
            both = left.join(right, how="inner", lsuffix="_a", rsuffix="_b")
            for m, column in enumerate(PAIRED):
                result = campaign_stats.paired_relative_difference(
                    both[column + "_a"], both[column + "_b"], seed=[seed, int(cell), i, j, m], resamples=resamples)
                if result is None:
                    continue
                rows.append({"cell": int(cell), "cell_label": cell_label(group.iloc[0], swept), "a": a, "b": b,
                             "metric": column, "pairs": result["pairs"],
                             "relative_difference_median": result["median"],
                             "relative_difference_ci95": [result["low"], result["high"]]})
    return rows


def sentence(row):
    name = next(text for column, text, _ in METRICS if column == row["metric"])
    median = row["relative_difference_median"]
    low, high = row["relative_difference_ci95"]
    word = "larger" if median > 0 else "smaller"
    text = (f"{row['a']}'s {name} is {abs(median) * 100:.1f} % {word} than {row['b']}'s "
            f"(a/b - 1 = {median * 100:+.1f} %, 95 % CI {low * 100:+.1f} to {high * 100:+.1f} %)")
    if low <= 0.0 <= high:
        text += " (the interval includes 0: no clear difference)"
    text += f", median over {row['pairs']} paired draws"
    if row["pairs"] < SMALL_SAMPLE:
        text += f" (fewer than {SMALL_SAMPLE}: the interval is rough, fly more draws before leaning on it)"
    return text


def markdown(meta, per_label, paired, seed, resamples):
    lines = [f"# Campaign {meta['campaign_name']}", "",
             f"Database: {meta['run_count']} runs, campaign file SHA-256 `{meta['campaign_sha256']}`.",
             "Completion: Wilson 95 % interval. Metrics over completed runs: mean / median / p90 / p99 / max "
             f"(numpy quantiles, method '{campaign_stats.QUANTILE_METHOD}'). Paired differences: median of a/b - 1 "
             f"over the draws both completed, percentile bootstrap 95 % ({resamples} resamples, seed {seed}).", ""]
    header = "| cell | label | completed | rate (95 % CI) | " + " | ".join(
        f"{text} [{unit}]" if unit else text for _, text, unit in METRICS) + " | not completed |"
    lines += [header, "|" + "---|" * (5 + len(METRICS))]
    for row in per_label:
        cells = []
        for column, _, _ in METRICS:
            s = row["metrics"][column]
            cells.append("-" if s["n"] == 0 else
                         f"{s['mean']:.4g} / {s['median']:.4g} / {s['p90']:.4g} / {s['p99']:.4g} / {s['max']:.4g}")
        low, high = row["completion_ci95"]
        reasons = "; ".join(f"{k}: {v}" for k, v in row["not_completed_reasons"].items()) or "-"
        lines.append(f"| {row['cell_label']} | {row['label']} | {row['completed']}/{row['runs']} | "
                     f"{row['completion_rate'] * 100:.1f} % ({low * 100:.1f}-{high * 100:.1f} %) | "
                     + " | ".join(cells) + f" | {reasons} |")
    if paired:
        lines += ["", "## Paired differences"]
        current = None
        for row in paired:
            if row["cell_label"] != current:
                current = row["cell_label"]
                lines += ["", f"**{current}**", ""]
            lines.append("- " + sentence(row))
    return "\n".join(lines) + "\n"


def write_atomically(path, text):
    partial = path + ".partial"
    with open(partial, "w", encoding="utf-8") as out:
        out.write(text)
    os.replace(partial, path)


def build_report(database, seed=1, resamples=2000):
    """The report of a campaign database of any version this report reads, under version 5's names:
    its meta table, its runs (a DataFrame, one row per run, each (cell, scenario) a cell), the
    per-label rows, the paired rows and report.json's content without the figures."""
    meta, runs = read_campaign(database)
    if runs.empty:
        raise ReportError(f"{database}: no runs stored yet")
    labels = json.loads(meta["labels"])
    runs, swept = by_scenario(runs, json.loads(meta["swept"]))
    per_label = controller_rows(runs, labels, swept)
    paired = paired_rows(runs, labels, swept, seed, resamples)
    for row in paired:
        row["sentence"] = sentence(row)
    report = {"format": "thetad-campaign-report-1", "format_version": REPORT_FORMAT_VERSION,
              "campaign": meta["campaign_name"],
              "campaign_sha256": meta["campaign_sha256"], "runs_stored": int(len(runs)),
              "run_count": int(meta["run_count"]), "provenance": json.loads(meta["provenance"]),
              "statistics": {"wilson_confidence": 0.95, "quantile_method": campaign_stats.QUANTILE_METHOD,
                             "bootstrap": {"method": "percentile", "resamples": resamples, "seed": seed},
                             "small_sample_pairs": SMALL_SAMPLE},
              "controllers": per_label, "paired": paired}
    return meta, runs, swept, report


def write_report(meta, runs, swept, report, out):
    """Writes report.md, report.json and the figures into `out`; returns the figures' files."""
    os.makedirs(out, exist_ok=True)
    labels = json.loads(meta["labels"])
    figures = plot_campaign.draw_figures(runs, report["controllers"], labels, swept, out)
    report["figures"] = figures
    statistics = report["statistics"]["bootstrap"]
    write_atomically(os.path.join(out, "report.json"), json.dumps(report, indent=1) + "\n")
    write_atomically(os.path.join(out, "report.md"), markdown(meta, report["controllers"], report["paired"],
                                                             statistics["seed"], statistics["resamples"]))
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("database")
    parser.add_argument("out")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--resamples", type=int, default=2000)
    args = parser.parse_args()
    try:
        meta, runs, swept, report = build_report(args.database, args.seed, args.resamples)
    except ReportError as error:
        raise SystemExit(str(error)) from None
    figures = write_report(meta, runs, swept, report, args.out)
    print(f"wrote report.md, report.json and {len(figures)} figures to {args.out}")


if __name__ == "__main__":
    main()
