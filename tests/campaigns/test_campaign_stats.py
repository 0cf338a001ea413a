"""The report's statistics (scripts/campaign_stats.py) against values computed independently:
the Wilson interval's closed form and a published example, the type-7 quantile by its definition,
and a percentile bootstrap written out here with its own generator."""

import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
import campaign_stats  # noqa: E402


def wilson_closed_form(k, n, z=1.959963984540054):
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return centre - half, centre + half


@pytest.mark.parametrize("k,n", [(0, 10), (1, 10), (7, 20), (20, 20), (81, 263), (199, 200), (500, 1000)])
def test_wilson_interval_is_the_closed_form(k, n):
    low, high = campaign_stats.wilson_interval(k, n)
    expected_low, expected_high = wilson_closed_form(k, n)
    assert low == pytest.approx(expected_low, abs=1e-12)
    assert high == pytest.approx(expected_high, abs=1e-12)


def test_wilson_interval_matches_newcombe_1998():
    # Newcombe (1998), Statistics in Medicine 17:857, Table I, method 3 (score, no correction):
    # 81/263 -> 0.2553 to 0.3662; 15/148 -> 0.0624 to 0.1605; 0/20 -> 0 to 0.1611.
    for (k, n), (low, high) in {(81, 263): (0.2553, 0.3662), (15, 148): (0.0624, 0.1605),
                                (0, 20): (0.0, 0.1611)}.items():
        got = campaign_stats.wilson_interval(k, n)
        assert got[0] == pytest.approx(low, abs=5e-5)
        assert got[1] == pytest.approx(high, abs=5e-5)


def type7_quantile(values, q):
    # Hyndman & Fan (1996) definition 7: h = (n - 1) q, interpolate between order statistics.
    x = sorted(values)
    h = (len(x) - 1) * q
    lo = math.floor(h)
    hi = min(lo + 1, len(x) - 1)
    return x[lo] + (h - lo) * (x[hi] - x[lo])


def test_summary_quantiles_are_type_7():
    rng = np.random.default_rng(3)
    values = rng.lognormal(size=137)
    s = campaign_stats.summary(values)
    assert s["n"] == 137
    assert s["mean"] == pytest.approx(sum(values) / len(values), rel=1e-14)
    assert s["median"] == pytest.approx(type7_quantile(values, 0.5), rel=1e-14)
    assert s["p90"] == pytest.approx(type7_quantile(values, 0.9), rel=1e-14)
    assert s["p99"] == pytest.approx(type7_quantile(values, 0.99), rel=1e-14)
    assert s["max"] == max(values)
    assert math.isnan(campaign_stats.summary([])["median"])


def test_paired_bootstrap_agrees_with_a_hand_written_percentile_bootstrap():
    rng = np.random.default_rng(11)
    b = rng.lognormal(mean=0.0, sigma=0.3, size=400)
    a = b * (1.08 + 0.03 * rng.standard_normal(400))  # a is 8 % larger, paired draw by draw
    result = campaign_stats.paired_relative_difference(a, b, seed=5, resamples=4000)
    ratios = a / b - 1.0
    assert result["pairs"] == 400
    assert result["median"] == pytest.approx(np.median(ratios), rel=1e-14)
    # The percentile interval by its definition, with an unrelated generator: the two agree to the
    # Monte-Carlo error of 4000 resamples (a few percent of the interval's width).
    other = np.random.default_rng(12345)
    medians = np.median(ratios[other.integers(0, ratios.size, size=(4000, ratios.size))], axis=1)
    low, high = np.quantile(medians, [0.025, 0.975])
    width = high - low
    assert result["low"] == pytest.approx(low, abs=0.1 * width)
    assert result["high"] == pytest.approx(high, abs=0.1 * width)
    assert result["low"] < 0.08 < result["high"]
    # Seeded: the same interval every time.
    assert campaign_stats.paired_relative_difference(a, b, seed=5, resamples=4000) == result
    assert campaign_stats.paired_relative_difference(a[:1], b[:1], seed=5) is None


def test_reason_kind_drops_numbers_and_times():
    assert campaign_stats.reason_kind("roll |phi| = 1.5 rad exceeds 1.48 rad at t = 3.2000 s") == "roll |phi|"
    assert campaign_stats.reason_kind("controller failed at t = 0.5000 s: CARE: no solution") == "controller failed"
    assert campaign_stats.reason_kind("non-finite state at t = 1.0000 s") == "non-finite state"


def test_the_report_keeps_scenarios_apart():
    import pandas as pd
    import campaign_report
    runs = pd.DataFrame({"cell": [0, 0, 1, 1], "scenario": ["b", "a", "b", "a"], "course": [0.0, 0.0, 90.0, 90.0]})
    split, swept = campaign_report.by_scenario(runs, ["course"])
    assert swept == ["course", "scenario"]
    assert list(split.cell) == [1, 0, 3, 2]
    assert campaign_report.cell_label(split.iloc[2], swept) == "course=90, scenario=b"
    one, same = campaign_report.by_scenario(runs[runs.scenario == "a"], ["course"])
    assert same == ["course"] and list(one.cell) == [0, 1]
