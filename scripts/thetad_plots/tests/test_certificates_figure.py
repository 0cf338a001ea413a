"""The certificates figure (thetad_plots.certificates) on small result folders written here."""

import json

import numpy as np
import pytest

from thetad_plots import certificates
from thetad_plots.results import PlotError
from thetad_plots.style import plt

COLUMNS = {"sdre": ["condition_estimate", "forward_error_estimate", "stabilizability_margin"], "theta-d": ["last_term_ratio"]}


def write_folder(folder, status="completed", certificates_on=True):
    folder.mkdir()
    t = np.linspace(0.0, 1.0, 11)
    for label, names in COLUMNS.items():
        names = names if certificates_on else []
        columns = [{"name": "t", "unit": "s"}] + [{"name": name, "unit": ""} for name in names]
        rows = np.column_stack([t] + [1.0 + t * (k + 1) for k in range(len(names))])
        header = ",".join(["t_s", *names])
        np.savetxt(folder / f"{label}.csv", rows, delimiter=",", header=header, comments="")
        result = {"status": status, "end_time_s": 1.0, "log": {"csv": f"{label}.csv", "columns": columns},
                  "certificates": {name: {"worst": "largest", "value": 2.0, "t_s": 1.0} for name in names}}
        (folder / f"{label}.json").write_text(json.dumps(result), encoding="utf-8")
    return folder


def test_one_column_of_panels_per_flight_the_share_on_a_log_axis(tmp_path):
    flights = certificates.read_flights([f"I={write_folder(tmp_path / 'a')}",
                                         f"stress={write_folder(tmp_path / 'b', status='diverged')}"])
    fig = certificates.draw(flights)
    axes = np.array(fig.axes).reshape(3, 2)
    assert [ax.get_title() for ax in axes[0]] == ["I", "stress"]
    assert [ax.get_yscale() for ax in axes[:, 0]] == ["linear", "linear", "log"]
    margin = axes[1][0].lines[0]
    assert np.allclose(margin.get_ydata(), 1.0 + np.linspace(0.0, 1.0, 11) * 3)
    plt.close(fig)


def test_a_run_without_certificates_is_refused_by_name(tmp_path):
    flights = certificates.read_flights([f"I={write_folder(tmp_path / 'a', certificates_on=False)}"])
    with pytest.raises(PlotError, match="no column condition_estimate .*certificates: on"):
        certificates.draw(flights)


def test_a_pair_without_a_folder_is_refused(tmp_path):
    with pytest.raises(PlotError, match="expected TITLE=FOLDER"):
        certificates.read_flights([str(tmp_path)])
