"""thetad.campaign_report: a campaign database's statistics as pandas DataFrames (and, with `out`,
the report files and figures `thetad campaign report` writes), by the shipped campaign_report.py."""

import dataclasses
import importlib.util
import os
import sys

import pandas as pd

from . import _thetad


@dataclasses.dataclass
class CampaignReport:
    """Named as docs/glossary.md names them, whatever the database's format_version. runs: one row
    per stored run (the database's columns: label, controller, status, rms_error_m, ...).
    controllers: one row per label and cell (label, completed, runs, completion_rate,
    completion_ci95, metrics.<column>.{n, mean, median, p90, p99, max} over the completed runs,
    not_completed_reasons.<kind>). paired: the paired differences between labels (a, b, metric,
    pairs, relative_difference_median, relative_difference_ci95). report: report.json's content.
    figures: the files drawn (with `out`)."""
    runs: pd.DataFrame
    controllers: pd.DataFrame
    paired: pd.DataFrame
    report: dict
    figures: list

    def __repr__(self):
        return (f"CampaignReport({self.report['campaign']}: {self.report['runs_stored']} of "
                f"{self.report['run_count']} runs, {len(self.controllers)} controller rows)")


def _report_module():
    script = _thetad._shipped_script("campaign_report.py")
    if not os.path.isfile(script):
        raise _thetad.Error(f"the report script {script} is not installed")
    folder = os.path.dirname(script)
    if folder not in sys.path:
        sys.path.insert(0, folder)  # its own imports (campaign_stats, plot_campaign) sit beside it
    spec = importlib.util.spec_from_file_location("thetad_campaign_report", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _frame(rows):
    # Nested statistics (metrics, factors) become columns "metrics.cost_dev.median", ...
    return pd.json_normalize(rows) if rows else pd.DataFrame()


def campaign_report(folder, out=None, seed=1, resamples=2000):
    """The statistics of the campaign in `folder` (its campaign.sqlite, as campaign_run wrote it, or
    an earlier thetad: the report reads format_version 2 and later): a CampaignReport. With `out`, also writes report.md, report.json and the figures there. seed and
    resamples: the paired bootstrap's."""
    module = _report_module()
    database = os.path.join(os.fspath(folder), "campaign.sqlite")
    if not os.path.isfile(database):
        raise _thetad.Error(f"{database}: no campaign database (campaign_run(..., out={os.fspath(folder)!r}) writes it)")
    try:
        meta, runs, swept, report = module.build_report(database, seed, resamples)
    except module.ReportError as error:
        raise _thetad.Error(str(error)) from None
    figures = module.write_report(meta, runs, swept, report, os.fspath(out)) if out is not None else []
    return CampaignReport(runs, _frame(report["controllers"]), _frame(report["paired"]), report, figures)
