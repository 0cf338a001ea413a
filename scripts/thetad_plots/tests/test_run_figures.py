"""The figures of a flight (thetad_plots.run), checked on their matplotlib objects."""

import copy
import re

import numpy as np
import pytest
from matplotlib.collections import PolyCollection

from conftest import CONTROLLERS, run_set
from thetad_plots import results, run
from thetad_plots.style import plt

LABELS = CONTROLLERS.split(",")
UNIT = re.compile(r"\((m|m/s|deg|deg/s|N|s|µs|–)\)$")


def named_lines(ax):
    """Labels of the lines a legend would show (matplotlib hides labels starting with '_')."""
    return [line.get_label() for line in ax.get_lines() if not line.get_label().startswith("_")]


def value_axes(fig):
    """The time-history axes that overlay the runs (not the error or difference panels)."""
    return [ax for ax in fig.axes if not re.match(r"^(Δ|.* − cmd)", ax.get_ylabel())]


def all_text(fig):
    texts = [fig._suptitle.get_text() if fig._suptitle else ""] + [t.get_text() for t in fig.texts]
    for ax in fig.axes:
        legend = ax.get_legend()
        texts += [t.get_text() for t in legend.get_texts()] if legend else []
    texts += [t.get_text() for legend in fig.legends for t in legend.get_texts()]
    # Long entries are wrapped: read them as one line each.
    return "\n".join(text.replace("\n", " ") for text in texts)


@pytest.fixture(scope="module")
def figures(paper):
    drawn = run.draw_all(paper)
    yield drawn
    for fig in drawn.values():
        plt.close(fig)


def test_every_figure_is_drawn(figures):
    assert list(figures) == ["trajectory_3d", *(f.kind for f in run.TIME_FIGURES), "tracking_error",
                             "compute_time", "summary"]


@pytest.mark.parametrize("kind", [f.kind for f in run.TIME_FIGURES])
def test_time_histories_have_one_line_per_controller_and_units(figures, kind):
    fig = figures[kind]
    for ax in value_axes(fig):
        names = named_lines(ax)
        expected = LABELS + (["command"] if kind == "position" else [])
        assert names == expected, ax.get_ylabel()
        assert UNIT.search(ax.get_ylabel()), ax.get_ylabel()
    for ax in fig.axes:
        assert UNIT.search(ax.get_ylabel()), f"{kind}: no unit in '{ax.get_ylabel()}'"
    assert fig.axes[-1].get_xlabel() == "time t (s)"


def test_overlays_draw_narrower_lines_on_top(figures):
    """Where runs agree, the lines drawn later (higher zorder) are narrower, so every run shows."""
    for ax in value_axes(figures["position"]):
        lines = [line for line in ax.get_lines() if line.get_label() in LABELS]
        ordered = sorted(lines, key=lambda line: line.get_zorder())
        widths = [line.get_linewidth() for line in ordered]
        assert widths == sorted(widths, reverse=True) and len(set(widths)) == len(widths)
        assert len({line.get_marker() for line in lines}) == len(lines)
        assert len({line.get_color() for line in lines}) == len(lines)


def test_position_has_error_panels_and_angles_difference_panels(figures, paper):
    position = [ax.get_ylabel() for ax in figures["position"].axes]
    assert position == ["x (m)", "x − cmd (m)", "y (m)", "y − cmd (m)", "altitude h (m)", "h − cmd (m)"]
    for ax in figures["position"].axes[1::2]:
        assert [line.get_label().lstrip("_") for line in ax.get_lines()][:len(LABELS)] == LABELS
    angles = [ax.get_ylabel() for ax in figures["euler_angles"].axes]
    assert angles == ["roll φ (deg)", "Δφ (deg)", "pitch θ (deg)", "Δθ (deg)", "yaw ψ (deg)", "Δψ (deg)"]
    difference = figures["euler_angles"].axes[1]
    # One line per run but the baseline, against which they are taken.
    drawn = [line.get_label().lstrip("_") for line in difference.get_lines()]
    assert [label for label in drawn if label in LABELS] == LABELS[1:]
    assert f"Δ: difference to {paper.baseline}" in all_text(figures["euler_angles"])


def test_error_panel_is_the_tracking_error(paper, figures):
    ax = figures["position"].axes[1]
    line = next(line for line in ax.get_lines() if line.get_label() == "_theta-d")
    d = paper.runs[0].data
    t, e = line.get_data()
    assert np.allclose(e, np.interp(t, d["t"], d["x_p"] - d["x_c"]))


def test_3d_trajectory_has_equal_scales(figures):
    ax = figures["trajectory_3d"].axes[0]
    spans = np.array([np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())])
    aspect = np.array(ax.get_box_aspect())
    assert np.allclose(aspect / aspect[0], spans / spans[0])
    assert [ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()] == ["x (m)", "y (m)", "h (m)"]
    assert named_lines(ax) == LABELS + ["command"]


def test_figure_numbers_follow_the_paper(flights):
    """Scenario I: Figs. 2–9, scenario II: Figs. 10–17, in the order trajectory, position, Euler
    angles, rates, velocities, flapping, deflections, thrust; none for other scenarios or the
    comparison figures."""
    kinds = ["trajectory_3d", *(f.kind for f in run.TIME_FIGURES)]
    for scenario, numeral, first in (("scenario-1", "I", 2), ("scenario-2", "II", 10)):
        drawn = run.draw_all(run_set(flights["paper"], scenario=scenario))
        for number, kind in enumerate(kinds, first):
            assert f"(cf. paper Fig. {number})\nscenario {numeral}," in drawn[kind]._suptitle.get_text(), kind
        for kind in ("tracking_error", "compute_time", "summary"):
            assert "Fig." not in drawn[kind]._suptitle.get_text()
        for fig in drawn.values():
            plt.close(fig)


def test_other_scenarios_name_no_paper_figure(figures):
    for kind, fig in figures.items():
        assert "Fig." not in fig._suptitle.get_text(), kind
        assert "climb" in fig._suptitle.get_text()


def test_divergence_is_marked_only_on_diverged_runs(flights, figures):
    for kind, fig in figures.items():
        assert "diverged" not in all_text(fig), kind
    drawn = run.draw_all(run_set(flights["paper"], not_completed="lqr"))
    for kind in ("position", "euler_angles", "trajectory_3d", "tracking_error"):
        text = all_text(drawn[kind])
        assert "lqr: diverged at t = 2.50 s (roll |phi| = 1.2 rad exceeds 1.0472 rad)" in text, kind
        assert text.count("diverged at") == 1, kind
    assert "hatched: diverged" in drawn["summary"]._suptitle.get_text()
    assert [t.get_text() for t in drawn["summary"].axes[0].get_yticklabels()] == ["theta-d", "lqr\n(diverged)",
                                                                                  "example-pid"]
    for fig in drawn.values():
        plt.close(fig)


def test_a_failed_run_is_marked_failed_not_diverged(flights):
    drawn = run.draw_all(run_set(flights["paper"], not_completed="lqr", status="failed"))
    for kind in ("position", "euler_angles", "trajectory_3d", "tracking_error"):
        text = all_text(drawn[kind])
        assert "lqr: failed at t = 2.50 s (controller failed: CARE)" in text, kind
        assert "diverged" not in text, kind
    assert "hatched: failed" in drawn["summary"]._suptitle.get_text()
    assert [t.get_text() for t in drawn["summary"].axes[0].get_yticklabels()] == ["theta-d", "lqr\n(failed)",
                                                                                  "example-pid"]
    for fig in drawn.values():
        plt.close(fig)


def test_a_manifest_with_the_earlier_step_time_column_reads_the_same(flights, paper):
    """Result files before format_version 4 named the log's wall-clock column compute (compute_ns)."""
    earlier = copy.deepcopy(flights["paper"])
    for column in earlier["schema"]:
        if column["name"] == results.STEP_TIME:
            column["name"] = "compute"
    for entry in earlier["runs"]:
        entry["columns"] = ["compute" if c == results.STEP_TIME else c for c in entry["columns"]]
    read = results.load(earlier, run.NEEDED)
    for before, now in zip(read.runs, paper.runs):
        assert np.any(now.data[results.STEP_TIME] > 0)
        assert before.data[results.STEP_TIME].equals(now.data[results.STEP_TIME])


def test_summary_says_hatched_only_when_a_run_diverged(figures):
    assert "hatched" not in figures["summary"]._suptitle.get_text()


def test_summary_labels_do_not_overlap(figures):
    fig = figures["summary"]
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes = [label.get_window_extent(renderer) for label in fig.axes[0].get_yticklabels()]
    assert [label.get_text() for label in fig.axes[0].get_yticklabels()] == LABELS
    for a, b in zip(boxes, boxes[1:]):
        assert not a.overlaps(b)


def bands(ax):
    return [c for c in ax.collections if isinstance(c, PolyCollection)]


def test_noise_dominated_inputs_are_filtered_with_a_noise_band(figures, ideal):
    fig = figures["control_deflections"]
    collective = next(ax for ax in fig.axes if ax.get_ylabel().startswith("δ_col"))
    assert len(bands(collective)) == len(LABELS)
    assert "δ_col" in all_text(fig) and "low-pass" in all_text(fig) and "±2σ of the measured noise" in all_text(fig)
    # Without noise the same panel draws the plain command and its caption claims no filtering.
    quiet = run.draw_time_figure(ideal, next(f for f in run.TIME_FIGURES if f.kind == "control_deflections"))
    assert all(not bands(ax) for ax in quiet.axes)
    assert "low-pass" not in all_text(quiet)
    plt.close(quiet)


def test_compute_time_marks_the_budget_on_a_log_axis(figures):
    ax = figures["compute_time"].axes[0]
    assert ax.get_yscale() == "log"
    assert ax.get_ylabel() == "control() wall time (µs)"
    assert "budget at 1 kHz (1000 µs)" in all_text(figures["compute_time"])
    assert named_lines(ax)[:len(LABELS)] == LABELS


def test_a_unit_without_a_display_rule_is_shown_as_the_schema_writes_it():
    # A plug-in plant's own units plot unscaled, not refused.
    runs = results.RunSet("mine", 1, "ideal", "", [], {"inertia": "kg_m2", "theta_dot": "rad_per_s", "v": "m_per_kg"})
    assert runs.display("inertia") == ("kg_m2", 1.0)
    assert runs.display("v") == ("m/kg", 1.0)
    assert runs.display("theta_dot") == results.DISPLAY_UNITS["rad_per_s"]
