"""The shared style (thetad_plots.style)."""

import numpy as np
import pytest

from thetad_plots import approximation, style, tuning
from thetad_plots.style import plt


def test_every_label_of_a_figure_gets_its_own_look():
    labels = ["theta-d", "sdre", "lqr", "lqr-scheduled", "example-pid", "mine", "yours", "hover"]
    looks = style.looks(labels)
    assert len(set(looks.values())) == len(labels)
    # Told apart in grey print too: every look has its own dash pattern and marker.
    assert len({look.dashes for look in looks.values()}) == len({look.marker for look in looks.values()}) == len(labels)
    assert looks["theta-d"] == style.KNOWN["theta-d"]
    # Stable: the same label set gives the same looks, whatever else is drawn in another order.
    assert style.looks(list(reversed(labels))) == looks


def test_other_labels_take_colours_the_figure_does_not_show_yet():
    looks = style.looks(["theta-d", "lqr", "sdre-cold", "sdre-warm"])
    assert len({look.colour for look in looks.values()}) == 4


def test_no_controller_looks_like_the_reference():
    for look in [*style.KNOWN.values(), *style.SPARE]:
        assert look.colour.lower() != "#000000"


def test_save_writes_each_format_and_refuses_others(tmp_path):
    style.apply()
    fig, ax = plt.subplots(figsize=style.size(style.COLUMN, 0.6))
    ax.plot([0, 1], [0, 1], **style.line("theta-d", ["theta-d"]))
    paths = style.save(fig, str(tmp_path / "f"), ["png", "pdf", "svg"], dpi=100)
    assert [p[-3:] for p in paths] == ["png", "pdf", "svg"]
    assert (tmp_path / "f.pdf").read_bytes()[:4] == b"%PDF"
    with pytest.raises(ValueError, match="unknown figure format jpg"):
        style.save(plt.figure(), str(tmp_path / "g"), ["jpg"])


def test_sigma_curves_figure(tmp_path):
    csv = tmp_path / "sigma-curves.csv"
    csv.write_text(",".join(tuning.COLUMNS) + "\n0,1,1.00001,1.000001\n1,2,2.00002,2.000001\n2,3,3.00001,3.000002\n")
    assert tuning.main(["plot_tuning.py", str(csv), str(tmp_path / "tuning.png"), "--format", "png,svg"]) == 0
    assert (tmp_path / "tuning.png").exists() and (tmp_path / "tuning.svg").exists()
    fig = tuning.draw_sigma_curves(*tuning.read_curves(csv))
    top, bottom = fig.axes
    assert [l.get_label() for l in top.get_lines()] == tuning.CURVES
    assert top.get_ylabel() == "σmax(P) (10⁶, –)" and bottom.get_ylabel().endswith("(ppm)")
    assert bottom.get_xlabel() == "time t (s)"
    assert [line.get_label() for line in bottom.get_lines()][:2] == tuning.CURVES[1:]
    plt.close(fig)
    csv.write_text("t,sigma\n0,1\n")
    assert tuning.main(["plot_tuning.py", str(csv), str(tmp_path / "bad")]) == 1


def test_approximation_figure(tmp_path):
    csv = tmp_path / "approximation.csv"
    csv.write_text(",".join(approximation.COLUMNS) + ",u_sdre_0,u_theta_d_0\n"
                   "0,1e-6,0,2e-3,70,70.1\n0.01,2e-6,3e-7,1e-3,70,70.05\n0.02,4e-6,1e-7,5e-4,70,70.01\n")
    assert approximation.main(["plot_approximation.py", str(csv), str(tmp_path / "errors"), "--format", "png"]) == 0
    assert (tmp_path / "errors.png").exists()
    fig = approximation.draw_errors(*approximation.read_errors(csv))
    (ax,) = fig.axes
    assert [l.get_label() for l in ax.get_lines()] == approximation.CURVES
    assert ax.get_yscale() == "log" and ax.get_xlabel() == "time t (s)"
    assert np.isnan(ax.get_lines()[1].get_ydata()[0])  # the exact zero is left out of the log axis
    plt.close(fig)
    csv.write_text("t_s,sigma\n0,1\n")
    assert approximation.main(["plot_approximation.py", str(csv), str(tmp_path / "bad")]) == 1
