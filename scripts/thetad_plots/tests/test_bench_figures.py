"""The benchmark figures (thetad_plots.bench) on series whose answer is known."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from thetad_plots import bench
from thetad_plots.style import plt

NS = [6, 12, 18, 36, 72]


def series(times):
    return [(n, t, 0.95 * t, 1.05 * t) for n, t in zip(NS, times)]


def test_a_power_law_is_fitted_with_its_slope():
    fit = bench.fit_power_law(NS, [2.0 * n ** 3 for n in NS])
    assert fit.holds and fit.exponent == pytest.approx(3.0) and fit.r2 == pytest.approx(1.0)


def test_no_power_law_where_the_cost_is_flat_or_bends():
    flat = bench.fit_power_law(NS, [0.05, 0.052, 0.049, 0.051, 0.05])
    bending = bench.fit_power_law(NS, [1.0, 1.1, 1.3, 50.0, 2500.0])
    too_few = bench.fit_power_law(NS[:3], [n ** 2 for n in NS[:3]])
    assert not flat.holds and not bending.holds and not too_few.holds


def test_scaling_prints_slopes_only_where_a_power_law_holds():
    fig = bench.draw_scaling({"theta-d": series([n ** 3 for n in NS]), "lqr": series([0.05, 0.052, 0.049, 0.051, 0.05])},
                             {"theta-d": "θ–D", "lqr": "LQR"})
    ax = fig.axes[0]
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts[0] == "θ–D: slope 3.00 (R² 1.000)"
    assert texts[1].startswith("LQR: no power law")
    assert ax.get_xscale() == ax.get_yscale() == "log"
    assert [t.get_text() for t in ax.get_xticklabels()] == [str(n) for n in NS]
    fig.canvas.draw()
    labelled = [t for t in ax.get_yticklabels() if t.get_text() and ax.get_ylim()[0] <= t.get_position()[1] <= ax.get_ylim()[1]]
    assert len(labelled) >= 3
    assert ax.get_xlabel() == "state dimension n (m = n/3)" and ax.get_ylabel() == "CPU time per step (µs, median)"
    plt.close(fig)


def test_step_costs_are_boxes_per_row_with_the_budget():
    rng = np.random.default_rng(1)
    rows = {"theta-d/terms:3/passes:1": list(5 + rng.random(20)), "sdre-warm/passes:1": list(170 + 5 * rng.random(20)),
            "lqr": list(0.05 + 0.001 * rng.random(20))}
    fig = bench.draw_step_costs(rows, 1000.0)
    ax = fig.axes[0]
    assert ax.get_xscale() == "log"
    assert [t.get_text() for t in ax.get_yticklabels()] == list(rows)
    assert len([p for p in ax.patches]) == len(rows)
    assert any(np.allclose(line.get_xdata(), 1000.0) for line in ax.get_lines())
    assert "budget at 1 kHz" in [t.get_text().strip() for t in ax.texts]
    assert ax.get_xlabel() == "CPU time per control step (µs)"
    plt.close(fig)


def benchmark_json(rows):
    """Google Benchmark JSON with 5 repetitions of every (run_name, µs) row."""
    return {"context": {"date": "2026-01-01T00:00:00+00:00", "executable": "/x/controllers_bench", "load_avg": [0.1]},
            "benchmarks": [{"run_name": name, "run_type": "iteration", "cpu_time": us * (1 + 0.01 * k),
                            "time_unit": "us"} for name, us in rows for k in range(5)]}


def test_report_states_exponents_only_where_a_power_law_holds(tmp_path):
    """bench/report.py end to end: the table's exponent row and the figures of every format."""
    out = tmp_path / "bench"
    out.mkdir()
    (out / "controllers_bench.json").write_text(json.dumps(benchmark_json(
        [("theta-d/terms:3/passes:1", 5.0), ("sdre-warm/passes:1", 170.0), ("lqr", 0.05)])))
    (out / "scaling_bench.json").write_text(json.dumps(benchmark_json(
        [(f"control_step/theta-d/n:{n}", 0.01 * n ** 3) for n in NS] +
        [(f"control_step/lqr/n:{n}", t) for n, t in zip(NS, [0.05, 0.052, 0.049, 0.051, 0.05])])))
    doc = tmp_path / "docs" / "performance.md"
    doc.parent.mkdir()
    doc.write_text("# Performance\n")
    report = Path(__file__).resolve().parents[3] / "bench" / "report.py"
    done = subprocess.run([sys.executable, str(report), str(out), str(tmp_path), str(doc), "--format", "svg"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    exponents = next(line for line in doc.read_text().splitlines() if line.startswith("| exponent |"))
    assert exponents.startswith("| exponent | **3.00** | none (R² ")
    for figure in ("controllers_step", "scaling"):
        for fmt in ("png", "svg"):
            assert (doc.parent / "figures" / f"{figure}.{fmt}").exists()
