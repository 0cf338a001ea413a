"""The campaign report (scripts/campaign_report.py) reads a database of format_version 4, written
before docs/glossary.md's names, and gives its values under the new names: in its DataFrames and
report.json, in its figures, and through `thetad campaign report` (THETAD_BINARY, when given)."""

import json
import os
import shutil
import sqlite3
import statistics
import subprocess
import sys

import pandas as pd
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
sys.path.insert(0, os.path.dirname(__file__))
import campaign_report  # noqa: E402
import campaign_stats  # noqa: E402
import version4_database as v4  # noqa: E402


@pytest.fixture
def old_folder(tmp_path):
    folder = tmp_path / "old"
    folder.mkdir()
    v4.write(folder / "campaign.sqlite")
    return folder


def as_version_5(source, target):
    """The same runs as a version-5 database: the columns and meta renamed, the registered names added."""
    shutil.copy(source, target)
    with sqlite3.connect(target) as db:
        columns = [row[1] for row in db.execute("PRAGMA table_info(runs)")]
        for old, new in campaign_report.OLD_NAMES.items():
            if old in columns:
                db.execute(f"ALTER TABLE runs RENAME COLUMN {old} TO {new}")
        db.execute("ALTER TABLE runs ADD COLUMN controller TEXT")
        db.execute("UPDATE runs SET controller = CASE label WHEN 'td' THEN 'theta-d' ELSE label END")
        db.execute("UPDATE meta SET key = 'labels' WHERE key = 'controllers'")
        db.execute("UPDATE meta SET value = ? WHERE key = 'swept'", (json.dumps(["initial_offset_x_m"]),))
        db.execute("UPDATE meta SET value = '5' WHERE key = 'format_version'")
    db.close()


def test_a_version_4_database_gives_its_values_under_the_new_names(old_folder):
    meta, runs, swept, report = campaign_report.build_report(str(old_folder / "campaign.sqlite"), resamples=200)
    assert swept == ["initial_offset_x_m"]
    assert json.loads(meta["labels"]) == v4.LABELS
    assert not set(campaign_report.OLD_NAMES) & set(runs.columns)
    assert list(runs.label[:2]) == v4.LABELS
    assert list(runs.initial_offset_x_m.unique()) == v4.OFFSETS and (runs.duration_s == 1.0).all()
    first = runs.iloc[0]
    assert (first.rms_error_x_m, first.max_axis_error_m) == pytest.approx((0.06, 0.2))
    assert (first.rms_command_T_mr_N, first.rms_command_delta_lat_rad) == (60.0, 0.04)
    assert (first.in_flight_step_time_median_us, first.wall_time_s) == (4.0, 0.25)

    rows = {(r["cell"], r["label"]): r for r in report["controllers"]}
    td = rows[(0, "td")]
    assert td["cell_label"] == "initial_offset_x_m=0"
    assert td["metrics"]["rms_error_m"]["median"] == pytest.approx(0.11)
    assert td["metrics"]["max_axis_error_m"]["max"] == pytest.approx(0.24)
    assert td["metrics"]["rms_command_T_mr_N"]["mean"] == pytest.approx(61.0)
    assert td["metrics"]["in_flight_step_time_mean_us"]["median"] == pytest.approx(6.0)
    lqr = rows[(1, "lqr")]
    assert (lqr["completed"], lqr["runs"]) == (2, 3)
    assert lqr["completion_ci95"] == pytest.approx(list(campaign_stats.wilson_interval(2, 3)))
    assert lqr["not_completed_reasons"] == {"roll |phi|": 1}
    assert lqr["metrics"]["cost"]["max"] == pytest.approx(310.0)

    paired = next(p for p in report["paired"] if p["cell"] == 0 and p["metric"] == "rms_error_m")
    ratios = [v4.rms_error("td", 0, d) / v4.rms_error("lqr", 0, d) - 1 for d in range(v4.DRAWS)]
    assert (paired["a"], paired["b"], paired["pairs"]) == ("td", "lqr", 3)
    assert paired["relative_difference_median"] == pytest.approx(statistics.median(ratios))
    low, high = paired["relative_difference_ci95"]
    assert low <= paired["relative_difference_median"] <= high
    assert "td's RMS 3-D position error is" in paired["sentence"]


def test_a_version_4_database_reports_as_the_same_runs_in_version_5(old_folder, tmp_path):
    as_version_5(old_folder / "campaign.sqlite", tmp_path / "new.sqlite")
    _, old_runs, _, old_report = campaign_report.build_report(str(old_folder / "campaign.sqlite"), resamples=200)
    _, new_runs, _, new_report = campaign_report.build_report(str(tmp_path / "new.sqlite"), resamples=200)
    assert old_report == new_report
    pd.testing.assert_frame_equal(old_runs, new_runs.drop(columns="controller"))


def test_the_figures_and_the_command_line_read_a_version_4_database(old_folder, tmp_path):
    report_of = campaign_report.build_report(str(old_folder / "campaign.sqlite"), resamples=200)
    figures = campaign_report.write_report(*report_of, str(tmp_path / "report"))
    assert {"cdf_rms_error.png", "completion.png", "paired_violins.png"} <= set(figures)
    assert all(os.path.getsize(tmp_path / "report" / name) > 1000 for name in figures)
    written = json.loads((tmp_path / "report" / "report.json").read_text())
    assert written["format_version"] == campaign_report.REPORT_FORMAT_VERSION
    markdown = (tmp_path / "report" / "report.md").read_text()
    assert "| initial_offset_x_m=0.5 | lqr | 2/3 |" in markdown
    thetad = os.environ.get("THETAD_BINARY")
    if not thetad:
        pytest.skip("THETAD_BINARY not given: `thetad campaign report` not run")
    result = subprocess.run([thetad, "campaign", "report", str(old_folder), "--out", str(tmp_path / "cli"),
                             "--resamples", "200"], capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "cli" / "report.md").read_text() == markdown


def test_one_swept_factor_over_two_scenarios_draws_its_envelope(old_folder, tmp_path):
    # The scenario becomes the envelope's second axis, a name rather than a number.
    with sqlite3.connect(old_folder / "campaign.sqlite") as db:
        db.execute("UPDATE runs SET scenario = 'hover-to-hover' WHERE cell = 1")
    db.close()
    report_of = campaign_report.build_report(str(old_folder / "campaign.sqlite"), resamples=200)
    assert report_of[2] == ["initial_offset_x_m", "scenario"]
    figures = campaign_report.write_report(*report_of, str(tmp_path / "report"))
    assert {"envelope_td.png", "envelope_lqr.png"} <= set(figures)
