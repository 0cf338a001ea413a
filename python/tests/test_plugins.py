"""A controller from a plug-in, named in no list (tests/plugins/test_only_controller_plugin.cpp),
reaches Python as it reaches the command line: listed, flown, compared through "all", benched."""

import os

import pytest

import thetad

PLUGIN = os.environ.get("THETAD_TEST_ONLY_PLUGIN")


@pytest.mark.skipif(not PLUGIN, reason="THETAD_TEST_ONLY_PLUGIN is set by CTest")
def test_a_plugin_controller_reaches_every_python_function():
    thetad.load_plugin(PLUGIN)
    thetad.load_plugin(PLUGIN)  # again: nothing happens
    listed = {c["name"]: c["origin"] for c in thetad.controllers()}
    assert "plug-in" in listed["test-only"]
    result = thetad.run("hover-to-hover", "test-only", duration_s=0.3, timing=False)
    assert result.completed and result.controller == "test-only"
    assert result.columns[-1] == "steps" and result.log[-1, -1] == 300  # its own log column (no timing)
    flown = [r.controller for r in thetad.compare("hover-to-hover", ["all"], duration_s=0.3, timing=False)]
    assert "test-only" in flown and "theta-d" in flown and "example-pid" not in flown
    report = thetad.bench(["test-only", "lqr"], scenario="hover-to-hover", duration_s=0.5, samples=20, segments=1,
                          repetitions=1, warmup=0)
    assert [row["iterations_mean"] for row in report["controllers"]] == [2.0, 0.0]


def test_a_missing_plugin_is_a_clear_error():
    with pytest.raises(thetad.Error, match="nowhere.so"):
        thetad.load_plugin("/nowhere.so")


def test_a_string_is_not_a_list_of_controllers():
    with pytest.raises(TypeError, match="expected a list"):
        thetad.compare("hover-to-hover", "theta-d", duration_s=0.1)
