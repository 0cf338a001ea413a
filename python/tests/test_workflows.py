"""The command line's workflows from Python: bench, optimal, plot, a campaign and its report, with
progress and Ctrl-C. Short flights: each test takes a few seconds."""

import json
import os
import shutil
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pandas as pd
import pytest

import thetad

# A campaign database written before docs/glossary.md's names (tests/campaigns, shared with the report's tests).
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests", "campaigns"))
import version4_database  # noqa: E402


def test_bench_returns_bench_json_with_the_table():
    report = thetad.bench(["theta-d", "fast=lqr"], scenario="hover-to-hover", duration_s=0.5, samples=50, segments=1,
                          repetitions=1, warmup=0)
    frame = pd.DataFrame(report["controllers"])
    assert list(frame.label) == ["theta-d", "fast"]
    assert (frame.calls >= 50).all() and (frame.step_time_median_us > 0).all()
    assert set(frame.verdict) <= {"capable", "marginal", "not capable"}
    assert report["recorded_with"] == "theta-d" and report["recording_status"] == "completed"
    assert report["recording_reason"] == "" and report["format_version"] == 2
    assert report["provenance"]["scenario"]["name"] == "hover-to-hover"
    assert "median us" in report["table"]


def test_optimal_reports_the_gap_on_j_dev_and_writes_what_the_command_writes(tmp_path):
    calls = []
    result = thetad.optimal("hover-to-hover", ["lqr"], horizon=0.2, control_interval=0.05, timing=False,
                            out=str(tmp_path), progress=lambda done, total: calls.append((done, total)))
    assert result.converged
    assert [run.label for run in result.runs] == ["lqr", "optimal"]
    report = result.report
    assert report["cost"]["name"] == "J_dev"
    (row,) = report["controllers"]
    assert row["label"] == "lqr" and row["cost"] >= row["optimal_cost"] > 0 and row["gap_percent"] >= 0
    assert json.loads((tmp_path / "optimality.json").read_text())["controllers"] == report["controllers"]
    assert (tmp_path / "comparison.json").is_file() and (tmp_path / "optimal.json").is_file()
    assert calls and calls[-1][0] == calls[-1][1]
    # Without out: the same report, the solves naming no file, nothing written.
    alone = thetad.optimal("hover-to-hover", ["lqr"], horizon=0.2, timing=False)
    assert "result" not in alone.report["optima"][0]["optimum"]
    assert alone.report["controllers"] == report["controllers"]


def test_progress_true_draws_a_bar_per_task(capfd):
    thetad.bench(["lqr"], scenario="hover-to-hover", duration_s=0.3, samples=20, segments=1, repetitions=1, warmup=0,
                 progress=True)
    thetad.run("hover-to-hover", "lqr", duration_s=0.3, summary_only=True, progress=True)
    err = capfd.readouterr().err
    assert "0.3" in err  # the flights' simulated seconds, on tqdm's bar or the plain lines


def test_optimal_refuses_a_label_the_optima_use():
    with pytest.raises(thetad.Error, match="labels starting 'optimal' name the optima"):
        thetad.optimal("hover-to-hover", ["optimal=lqr"], horizon=0.2)


def test_plot_draws_runs_in_memory_and_a_folder(tmp_path):
    runs = thetad.compare("scenario-1", ["theta-d", "lqr"], duration_s=0.5, timing=False)
    files = thetad.plot(runs, tmp_path / "a", formats="png", dpi=40)
    assert {os.path.basename(f) for f in files} >= {"position.png", "euler_angles.png"}
    assert all(os.path.getsize(f) > 0 for f in files)
    for run in runs:
        run.write(str(tmp_path / "runs"))
    assert len(thetad.plot(tmp_path / "runs", tmp_path / "b", formats=["png"], dpi=40)) == len(files)
    with pytest.raises(thetad.Error, match="baseline nobody: no run of"):
        thetad.plot(runs, tmp_path / "c", baseline="nobody")
    assert not (tmp_path / "c").exists()


FORMAT_3 = Path(__file__).resolve().parents[2] / "tests" / "fixtures" / "results" / "hover-to-hover-theta-d-format-3"


def test_plot_draws_results_of_earlier_format_versions(tmp_path):
    """Version 3 as an earlier thetad wrote it, and version 1 made from it (no format_version, no
    log.columns, no scenario text): read under the current names, drawn as they were."""
    shutil.copytree(FORMAT_3, tmp_path / "v3")
    shutil.copytree(FORMAT_3, tmp_path / "v1")
    result = json.loads((FORMAT_3 / "theta-d.json").read_text())
    assert result["format_version"] == 3 and "tracking_error_m" in result
    del result["format_version"], result["log"]["columns"], result["provenance"]["scenario"]["text"]
    (tmp_path / "v1" / "theta-d.json").write_text(json.dumps(result))
    for version in ("v3", "v1"):
        files = thetad.plot(tmp_path / version, tmp_path / f"{version}-figures", formats="png", dpi=40)
        assert {os.path.basename(f) for f in files} >= {"position.png", "summary.png", "compute_time.png"}


CAMPAIGN = textwrap.dedent("""
    campaign: python-small
    scenarios: [hover-to-hover]
    controllers:
      - {controller: theta-d}
      - {controller: lqr}
    draws: {count: DRAWS, base_seed: 1}
    fixed: {duration_s: DURATION}
""")


def campaign_file(folder, draws, duration):
    path = folder / "small.yaml"
    path.write_text(CAMPAIGN.replace("DRAWS", str(draws)).replace("DURATION", str(duration)))
    return str(path)


def test_a_campaign_runs_resumes_and_reports_as_dataframes(tmp_path):
    file = campaign_file(tmp_path, 3, 0.5)
    seen = []
    outcome = thetad.campaign_run(file, out=str(tmp_path / "out"), jobs=2, timing=False,
                                  progress=lambda done, total: seen.append((done, total)))
    assert outcome["runs"] == 6 and outcome["flown"] == 6 and outcome["campaign"] == "python-small"
    assert outcome["not_completed"] == 0
    assert seen[-1] == (6, 6)
    again = thetad.campaign_run(file, out=str(tmp_path / "out"), resume=True, timing=False)
    assert again["flown"] == 0
    report = thetad.campaign_report(tmp_path / "out", out=tmp_path / "report", resamples=200)
    assert len(report.runs) == 6 and set(report.runs.label) == {"theta-d", "lqr"}
    assert set(report.runs.controller) == {"theta-d", "lqr"}
    assert list(report.controllers.label) == ["theta-d", "lqr"]
    assert (report.controllers.completed == 3).all()
    assert "metrics.cost_dev.median" in report.controllers.columns
    # Three pairs: the interval comes with a caution.
    assert all("fewer than 10" in sentence for sentence in report.paired.sentence)
    assert (tmp_path / "report" / "report.md").is_file() and report.figures
    with pytest.raises(thetad.Error, match="no campaign database"):
        thetad.campaign_report(tmp_path / "nowhere")


def test_a_campaign_database_of_format_version_4_is_reported_under_the_new_names(tmp_path):
    version4_database.write(tmp_path / "campaign.sqlite")
    report = thetad.campaign_report(tmp_path, out=tmp_path / "report", resamples=200)
    assert list(report.runs.label[:2]) == version4_database.LABELS
    assert "initial_offset_x_m" in report.runs.columns and "max_axis_error_m" in report.runs.columns
    first = report.controllers.iloc[0]
    assert (first.label, first.completed) == ("td", 3)
    assert first["metrics.rms_error_m.median"] == pytest.approx(version4_database.rms_error("td", 0, 1))
    assert list(report.controllers["not_completed_reasons.roll |phi|"].fillna(0)) == [0, 0, 0, 1]
    assert set(report.paired.metric) == {"rms_error_m", "max_axis_error_m", "cost_dev", "cost"}
    assert "relative_difference_median" in report.paired.columns and report.figures


INTERRUPTED = textwrap.dedent("""
    import sys, time
    import thetad
    file, out = sys.argv[1:]
    print("flying", flush=True)
    try:
        thetad.campaign_run(file, out=out, jobs=2, timing=False)
        print("completed", flush=True)
    except KeyboardInterrupt as stop:
        print("interrupted", time.monotonic(), flush=True)
""")


def test_ctrl_c_stops_a_campaign_within_a_second_and_keeps_its_database_whole(tmp_path):
    file = campaign_file(tmp_path, 40, 600)  # hours of flying: only Ctrl-C ends it
    out = tmp_path / "out"
    child = subprocess.Popen([sys.executable, "-c", INTERRUPTED, file, str(out)], stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "flying"
        time.sleep(2.0)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        line = child.stdout.readline().split()
        assert child.wait(timeout=30) == 0
    finally:
        child.kill()
    assert line[0] == "interrupted", line
    assert float(line[1]) - sent < 1.0, f"KeyboardInterrupt {float(line[1]) - sent:.2f} s after SIGINT"
    # The database is whole: it holds the runs stored before the interrupt (or none), not all 80.
    try:
        stored = len(thetad.campaign_report(out, resamples=100).runs)
    except thetad.Error as error:
        assert "no runs stored yet" in str(error)
        stored = 0
    assert stored < 80
