"""The runs of one `thetad plot` manifest, read with pandas, in the units people read.

`thetad plot --in DIR` checks the result folder (hashes, schema, same flight) and hands this
package a manifest (JSON):

  {"out": "staging dir", "formats": ["png", "svg"], "dpi": 300, "baseline": "",
   "schema": [{"name": "t", "unit": "s"}, ...],          # thetad::sim::log_schema(), in order
   "runs": [{"name": "theta-d", "csv": "...", "columns": ["t", ...], "summary": {...result JSON...}}, ...]}

The CSV columns are known only through "schema": every column drawn is looked up there by name,
so a renamed column is a clear error here and nowhere else is the column list written down.
"""

import json
import math
import re
from dataclasses import dataclass

import pandas as pd


class PlotError(Exception):
    """A problem with the input, said in one line (the command prints it and exits with 1)."""


# How a schema unit is shown to people (docs/model.md §1: degrees for angles): (label, factor).
DISPLAY_UNITS = {
    "s": ("s", 1.0),
    "m": ("m", 1.0),
    "m_per_s": ("m/s", 1.0),
    "rad": ("deg", 180.0 / math.pi),
    "rad_per_s": ("deg/s", 180.0 / math.pi),
    "N": ("N", 1.0),
    "N_m": ("N m", 1.0),
    "ns": ("µs", 1e-3),
    "": ("–", 1.0),  # a plant's dimensionless signals (the RTAC/TORA benchmark's)
}

# The log's wall-clock column (docs/glossary.md "Compute time"); result files before format_version
# 4 named it compute (compute_ns), which reads as this name here.
STEP_TIME = "in_flight_step_time"
EARLIER_COLUMNS = {"compute": STEP_TIME}


@dataclass
class Run:
    label: str
    summary: dict
    data: pd.DataFrame  # the log's columns by schema name, SI units as logged

    @property
    def not_completed(self):
        """Whether the run diverged or failed (docs/glossary.md "How a run ended")."""
        return self.status != "completed"

    @property
    def status(self):
        return self.summary.get("status", "")

    @property
    def end_time(self):
        return float(self.summary["end_time_s"])

    def ending(self):
        """'diverged at t = 12.34 s (roll |phi| = 1.1 rad exceeds 1 rad)' or 'failed at t = 3.00 s (…)'
        for a run that did not complete, else ''. The reason is the result file's without the time
        it repeats, and of a failure's chain ('controller failed: main-rotor speed (A4): thrust
        T_mr = …') the first two links."""
        if not self.not_completed:
            return ""
        reason = re.sub(r" at t = [-+0-9.e]+ s", "", self.summary.get("reason", "")).strip()
        reason = ": ".join(reason.split(": ")[:2])
        return f"{self.status} at t = {self.end_time:.2f} s" + (f" ({reason})" if reason else "")


@dataclass
class RunSet:
    scenario: str
    seed: int
    setting: str  # "paper" (uncertainty, gust and noise on), "ideal" (all off) or "custom"
    baseline: str
    runs: list
    units: dict  # schema column -> unit

    @property
    def labels(self):
        return [run.label for run in self.runs]

    def display(self, column):
        """(unit label, factor from SI) of a schema column."""
        unit = self.units.get(column)
        if unit is None:
            raise PlotError(f"the thetad log schema has no column {column} (update thetad_plots)")
        # A unit without a rule (a plug-in plant's "kg_m2") is shown as the schema writes it, unscaled:
        # a plant of one's own plots without an edit here.
        return DISPLAY_UNITS.get(unit, (unit.replace("_per_", "/"), 1.0))

    def longest(self):
        """The run that flew longest: the command is the same for every run of a folder, and a run
        that did not complete logged only part of it."""
        return max(self.runs, key=lambda run: len(run.data))

    def base_run(self):
        return next(run for run in self.runs if run.label == self.baseline)


def setting_of(summary):
    settings = summary.get("settings", {})
    disturbed = [bool(settings.get("parameter_uncertainty")), bool(settings.get("wind_gust", {}).get("enabled")),
                 float(settings.get("noise", {}).get("measurement", 0)) > 0]
    return "paper" if all(disturbed) else "ideal" if not any(disturbed) else "custom"


def read_csv(run, needed):
    present = [name for name in needed if name in run["columns"]]
    try:
        data = pd.read_csv(run["csv"], header=0, names=run["columns"], usecols=present, dtype=float)
    except (OSError, ValueError) as e:
        raise PlotError(f"{run['csv']}: {e}") from e
    if data.empty:
        raise PlotError(f"{run['csv']}: no samples")
    # A run flown without timing has no step-time column: it reads as zeros ("not measured").
    for name in needed:
        if name not in data:
            if name != STEP_TIME:
                raise PlotError(f"{run['csv']}: no column {name}")
            data[name] = 0.0
    return data


def read_manifest(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise PlotError(f"cannot read the manifest {path}: {e}") from e


def load(manifest, needed):
    """The RunSet of a manifest (its JSON as a dict), with the columns `needed`."""
    if not manifest.get("runs"):
        raise PlotError("the manifest lists no runs")
    units = {EARLIER_COLUMNS.get(column["name"], column["name"]): column["unit"] for column in manifest["schema"]}
    missing = [name for name in needed if name not in units]
    if missing:
        raise PlotError("the thetad log schema has no column " + ", ".join(missing) +
                        " (thetad_plots needs it: update the figure definitions)")
    runs = [Run(r["name"], r["summary"], read_csv({**r, "columns": [EARLIER_COLUMNS.get(c, c) for c in r["columns"]]},
                                                  needed)) for r in manifest["runs"]]
    labels = [run.label for run in runs]
    baseline = manifest.get("baseline") or labels[0]
    if baseline not in labels:
        raise PlotError(f"baseline '{baseline}' is none of the runs ({', '.join(labels)})")
    first = runs[0].summary
    scenario = first.get("provenance", {}).get("scenario", {}).get("name", "")
    return RunSet(scenario, first.get("seed"), setting_of(first), baseline, runs, units)
