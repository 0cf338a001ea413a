"""thetad.run: the result, its log as numpy and pandas with the CSV's columns, reproducibility."""

import csv
import json
import math
import os

import numpy as np
import pandas as pd
import pytest

import thetad


@pytest.fixture(scope="module")
def flown():
    return thetad.run("scenario-1", "theta-d", seed=4, duration_s=0.5, timing=False)


def test_the_result_says_what_flew(flown):
    assert flown.completed and flown.status == flown.status_text == "completed" and flown.reason == ""
    assert (flown.label, flown.controller, flown.controller_origin) == ("theta-d", "theta-d", "built-in")
    assert flown.summary["controller_samples"] == 500
    assert flown.summary["rms_error_m"] == pytest.approx(
        math.sqrt(sum(flown.summary[f"rms_error_{axis}_m"] ** 2 for axis in "xyz")), rel=1e-12)
    assert flown.summary["cost"] > 0 and "in_flight_step_time_median_us" not in flown.summary
    assert flown.provenance["seed"] == 4 and flown.provenance["scenario"]["name"] == "scenario-1"
    assert flown.settings["terms"] == 3
    document = flown.json()
    assert document["format"] == "thetad-run-1" and document["label"] == "theta-d" and document["log"] is None


def test_the_log_as_numpy_and_pandas_has_the_csv_columns(flown, tmp_path):
    assert flown.log.shape == (500, len(flown.columns))
    assert flown.columns[:4] == ["t_s", "x_c_m", "y_c_m", "z_c_m"] and "in_flight_step_time_ns" not in flown.columns
    assert not flown.log.flags.writeable
    frame = flown.frame()
    assert isinstance(frame, pd.DataFrame) and list(frame.columns) == flown.columns
    np.testing.assert_array_equal(frame["t_s"].to_numpy(), np.arange(500) * 1e-3)
    frame.loc[0, "x_p_m"] = 1.0  # the frame is the user's copy; the result's log stays as flown
    assert flown.log[0, flown.columns.index("x_p_m")] == 0.0
    json_file, csv_file = flown.write(str(tmp_path))
    with open(csv_file) as stream:
        rows = list(csv.reader(stream))
    assert rows[0] == flown.columns
    np.testing.assert_array_equal(np.array(rows[1:], dtype=float), flown.log)
    with open(json_file) as stream:
        document = json.load(stream)
    assert document["label"] == "theta-d" and document["log"]["csv"] == os.path.basename(csv_file)
    assert document["log"]["rows"] == 500


def test_same_seed_same_result_bit_for_bit(flown):
    again = thetad.run("scenario-1", "theta-d", seed=4, duration_s=0.5, timing=False)
    np.testing.assert_array_equal(again.log, flown.log)
    other = thetad.run("scenario-1", "theta-d", seed=5, duration_s=0.5, timing=False)
    assert not np.array_equal(other.log, flown.log)


def test_summary_only_keeps_no_log():
    result = thetad.run("scenario-1", "lqr", duration_s=0.2, summary_only=True)
    assert result.log.shape == (0, len(result.columns)) and result.frame().empty
    assert "in_flight_step_time_ns" in result.columns  # with timing, as the CSV would have
    assert result.wall_time_s > 0 and result.summary["in_flight_step_time_median_us"] > 0


def test_duration_and_dt_keep_their_earlier_keyword_names():
    current = thetad.run("hover-step", "lqr", duration_s=0.02, dt_s=5e-4, summary_only=True, timing=False)
    earlier = thetad.run("hover-step", "lqr", duration=0.02, dt=5e-4, summary_only=True, timing=False)
    assert current.summary == earlier.summary
    assert current.summary["settings"]["duration_s"] == 0.02 and current.summary["settings"]["dt_s"] == 5e-4
    with pytest.raises(TypeError, match="give duration_s or its earlier name duration, not both"):
        thetad.run("hover-step", "lqr", duration_s=0.02, duration=0.02)


def test_actuator_limits_are_on_unless_turned_off():
    def limits(**controls):
        result = thetad.run("hover-to-hover", "lqr", duration_s=0.1, summary_only=True, timing=False, **controls)
        return result.summary["settings"]["actuator_limits"]["enabled"]

    assert limits() and not limits(actuator_limits=False) and not limits(ideal=True)
    assert limits(ideal=True, actuator_limits=True)


def test_the_campaign_factors_are_keywords_too():
    rough = thetad.run("scenario-1", "lqr", duration_s=0.3, timing=False, turbulence_model="dryden",
                       turbulence_intensity="severe", servo_time_constant_s=0.02, noise_scale=2)
    assert rough.json()["settings"]["turbulence"]["intensity"] == "severe"
    assert rough.json()["settings"]["servos"]["time_constant_s"] == [0.02] * 5
    with pytest.raises(ValueError, match="turbulence_intensity: expected one of light moderate severe"):
        thetad.run("scenario-1", "lqr", duration_s=0.1, turbulence_intensity="stormy")
    with pytest.raises(ValueError, match=r"noise_scale: value -1 is outside \[0"):
        thetad.run("scenario-1", "lqr", duration_s=0.1, noise_scale=-1)


def test_a_registered_controller_object_flies_as_its_spec():
    tuned = thetad.controller("tuned=theta-d", k=[0.5, 2.0], l=[0.1, 0.2])
    result = thetad.run("hover-step", tuned, duration_s=0.2, summary_only=True, timing=False)
    assert result.label == "tuned" and result.settings["k"] == [0.5, 2.0]


def test_certificates_are_log_columns_and_a_summary_section_when_on():
    checked = thetad.controller("sdre", certificates=True)
    result = thetad.run("scenario-1", checked, duration_s=0.05, timing=False)
    assert result.settings["certificates"] is True
    worst = result.summary["certificates"]["stabilizability_margin"]
    column = result.log[:, result.columns.index("stabilizability_margin")]
    assert worst["worst"] == "smallest" and worst["value"] == column.min() > 0
    assert "certificates" not in thetad.run("scenario-1", "sdre", duration_s=0.05, timing=False).summary


def test_bad_calls_raise():
    with pytest.raises(thetad.Error, match="scenario 'no-such-scenario'"):
        thetad.run("no-such-scenario", "lqr")
    with pytest.raises(thetad.Error, match="unknown controller"):
        thetad.run("scenario-1", "no-such-controller", duration_s=0.1)
    with pytest.raises(TypeError, match="unknown run control 'seeds'"):
        thetad.run("scenario-1", "lqr", seeds=3)
    with pytest.raises(thetad.Error, match="duration"):
        thetad.run("scenario-1", "lqr", duration_s=-1.0)
    with pytest.raises(TypeError, match="controller: expected"):
        thetad.run("scenario-1", 42)
    with pytest.raises(thetad.Error, match="label"):
        thetad.run("scenario-1", "lqr", label="bad label/")
