"""thetad.tune: the tuning library's run from Python (tuning/tune_run.hpp), on short flights. It
writes what `thetad tune` writes, returns tuning.json's content, reports its tasks to a progress
callback and stops at Ctrl-C with no result files."""

import json
import os

import pytest

import thetad
from interrupted import interrupt


def test_a_closed_loop_tune_of_the_series_writes_a_settings_file_that_flies(tmp_path):
    calls = []
    report = thetad.tune("scenario-1", objective="closed-loop", draws=1, holdout_draws=1, max_evaluations=2,
                         duration=1.0, timing=False, out=tmp_path, progress=lambda *call: calls.append(call))
    assert report["scenario"] == "scenario-1" and report["controller"] == "theta-d"
    assert report["objective"] == {"name": "closed-loop", "metric": "cost", "training_seeds": [1]}
    assert report["parameters"]["kind"] == "series"
    assert report["parameters"]["names"] == ["k1", "k2", "l1", "l2"]
    assert report["evaluations"] == 2 and report["stop_reason"] == "maxeval reached"
    assert report["tuned_mean_cost"] <= report["default_mean_cost"]
    assert [v["scenario"] for v in report["validation"]] == ["scenario-1", "scenario-2"]
    assert all(v["pairs"] == 1 and v["runs"][0]["seed"] == 2 for v in report["validation"])
    settings = tmp_path / "theta-d-tuned.yaml"
    assert report["tuned_settings"] == str(settings)
    assert report["files"] == [str(settings), str(tmp_path / "tuning.json")]
    written = json.loads((tmp_path / "tuning.json").read_text())
    assert written == {key: value for key, value in report.items() if key not in ("tuned_settings", "files")}

    # Each task from its start to its end, in order: the search's 2 evaluations, then each
    # validation's 2 flights (default and tuned, one held-out draw).
    assert all(len(call) == 2 for call in calls)
    assert [call for call in calls if call[0] == 0.0] == [(0.0, 2.0)] * 3
    assert calls[0] == (0.0, 2.0) and calls[-1] == (2.0, 2.0)

    tuned = thetad.run("scenario-1", f"tuned=theta-d:{settings}", duration=1.0, summary_only=True, timing=False)
    assert tuned.completed
    assert tuned.settings["k"] == report["k"] and tuned.settings["l"] == report["l"]


def test_the_sdre_weights_are_tuned_by_the_closed_loop(tmp_path):
    report = thetad.tune("scenario-1", "sdre", objective="closed-loop", draws=1, max_evaluations=2, duration=1.0,
                         timing=False, validation=False, seed=5, out=str(tmp_path / "sdre"))
    assert report["controller"] == "sdre" and report["parameters"]["kind"] == "weights"
    assert report["seed"] == 5 and report["objective"]["training_seeds"] == [5]
    assert len(report["parameters"]["tuned"]) == len(report["parameters"]["names"]) > 0
    assert report["validation"] == [] and "k" not in report
    assert report["tuned_settings"].endswith(os.path.join("sdre", "sdre-tuned.yaml"))
    tuned = thetad.run("scenario-1", f"tuned=sdre:{report['tuned_settings']}", duration=1.0, summary_only=True)
    assert tuned.completed and tuned.label == "tuned"


def test_the_rms_error_metric_is_still_accepted_by_its_former_name(tmp_path):
    report = thetad.tune("scenario-1", objective="closed-loop", metric="rms-error", draws=1, max_evaluations=1,
                         duration=0.5, timing=False, validation=False, out=tmp_path)
    assert report["format_version"] == 2
    assert report["objective"]["metric"] == "rms_error_m"
    assert report["tuned_mean_rms_error_m"] == report["default_mean_rms_error_m"] > 0


def test_bad_options_fail_before_anything_is_written(tmp_path):
    out = tmp_path / "never"
    with pytest.raises(thetad.Error, match="unknown objective 'speed'"):
        thetad.tune("scenario-1", objective="speed", out=out)
    with pytest.raises(thetad.Error, match="weights are tuned by the closed loop only"):
        thetad.tune("scenario-1", parameters="weights", out=out)
    with pytest.raises(thetad.Error, match="--k-bounds: expected a lower and an upper bound"):
        thetad.tune("scenario-1", k_bounds=[0.0], out=out)
    with pytest.raises(TypeError, match="unknown run control 'speed'"):
        thetad.tune("scenario-1", out=out, speed=2)
    with pytest.raises(TypeError, match=r"progress: expected None, True \(a bar\) or a callable progress\(done, total\)"):
        thetad.tune("scenario-1", out=out, progress=3)
    assert not out.exists()


# A tune far longer than the test: only Ctrl-C ends it, in the SDRE record's flight (sigma) or in the
# draws' flights of the search (closed-loop).
TUNE = 'thetad.tune("scenario-1", objective=sys.argv[2], draws=2, duration=3600.0, timing=False, out=sys.argv[1])'


@pytest.mark.parametrize("objective", ["sigma", "closed-loop"])
def test_ctrl_c_stops_a_tune_within_a_second_and_writes_no_result(tmp_path, objective):
    folder = tmp_path / "out"
    message = interrupt("", TUNE, folder, objective, after=1.5)
    assert "stopped" in message and "no result" in message
    assert list(folder.iterdir()) == []
