"""Fixtures of the figure tests: a short comparison flown by the built thetad ($THETAD_BINARY,
set by CTest), the manifest `thetad plot` writes for it, and the RunSet read from it."""

import copy
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from thetad_plots import results, run, style  # noqa: E402  (found through the path above)

CONTROLLERS = "theta-d,lqr,example-pid"
# A 2 s climb to 0.5 m, then 0.5 s sideways: long enough for the noise to show, short to fly.
SCENARIO = """name: climb
duration: 2.5
phases:
  - name: climb
    type: ramp
    time: [0, 2]
    to: [0, 0, 0.5]
  - name: side
    type: ramp
    time: [2, 2.5]
    to: [0, 0.2, 0.5]
"""


def thetad(*arguments, env=None):
    binary = os.environ.get("THETAD_BINARY")
    if not binary:
        pytest.skip("THETAD_BINARY is not set (CTest sets it to the built thetad)")
    done = subprocess.run([binary, *arguments], capture_output=True, text=True, env=env)
    assert done.returncode == 0, done.stderr
    return done


def manifest_of(folder, tmp):
    """The manifest `thetad plot` writes for a result folder, as a dict."""
    captured = tmp / f"{folder.name}-manifest.json"
    thetad("plot", "--in", str(folder), "--out", str(tmp / f"{folder.name}-placeholder"), "--script",
           str(Path(__file__).with_name("capture_manifest.py")),
           env={**os.environ, "THETAD_TEST_MANIFEST": str(captured)})
    return json.loads(captured.read_text())


@pytest.fixture(scope="session")
def flights(tmp_path_factory):
    """{'paper': manifest, 'ideal': manifest} of the climb flown by CONTROLLERS."""
    tmp = tmp_path_factory.mktemp("figures")
    (tmp / "climb.yaml").write_text(SCENARIO)
    manifests = {}
    for setting, extra in (("paper", []), ("ideal", ["--ideal"])):
        folder = tmp / setting
        thetad("compare", "--scenario", str(tmp / "climb.yaml"), "--controllers", CONTROLLERS, "--seed", "1",
               "--out", str(folder), *extra)
        manifests[setting] = manifest_of(folder, tmp)
    style.apply()
    style.plt.rcParams["figure.max_open_warning"] = 0  # the tests close what they draw, some at the end
    return manifests


REASONS = {"diverged": "roll |phi| = 1.2 rad exceeds 1.0472 rad at t = 2.5000 s",
           "failed": "controller failed at t = 2.5000 s: CARE: no stabilizing solution: the pair is not stabilizable"}


def run_set(manifest, scenario=None, not_completed=None, status="diverged"):
    """The RunSet of a manifest, as if flown on `scenario` and with the run `not_completed` (label)
    ended as `status` (diverged or failed) at its last sample: both edit a copy of the manifest,
    not the files."""
    manifest = copy.deepcopy(manifest)
    for entry in manifest["runs"]:
        if scenario:
            entry["summary"]["provenance"]["scenario"]["name"] = scenario
        if entry["name"] == not_completed:
            entry["summary"].update(status=status, reason=REASONS[status])
    return results.load(manifest, run.NEEDED)


@pytest.fixture(scope="session")
def paper(flights):
    return run_set(flights["paper"])


@pytest.fixture(scope="session")
def ideal(flights):
    return run_set(flights["ideal"])
