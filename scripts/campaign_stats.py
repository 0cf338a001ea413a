"""The statistics of a campaign report, each taken from a library rather than written out here.

- completion rate: the Wilson score interval (statsmodels.stats.proportion.proportion_confint,
  method="wilson"), which keeps its coverage near 0 % and 100 % where the normal interval fails;
- quantiles: numpy.quantile with method="linear" (Hyndman & Fan's type 7, numpy's and R's default);
- paired differences: the median of the per-draw relative differences between two controllers
  flown on the same draws, with a percentile bootstrap interval (scipy.stats.bootstrap) from a
  seeded generator, so a report is the same every time it is made.
"""

import re

import numpy as np
from scipy import stats
from statsmodels.stats.proportion import proportion_confint

QUANTILE_METHOD = "linear"
SUMMARY_QUANTILES = {"median": 0.5, "p90": 0.9, "p99": 0.99}


def wilson_interval(successes, trials, confidence=0.95):
    """The Wilson score interval of a binomial proportion: (low, high)."""
    low, high = proportion_confint(successes, trials, alpha=1.0 - confidence, method="wilson")
    return float(low), float(high)


def summary(values):
    """Mean, median, p90, p99 and max of `values` (NaN for an empty sample); NULL values (a figure
    the run does not have: no timing, no J_dev) are not part of the sample."""
    values = np.asarray(values, dtype=float)
    values = values[~np.isnan(values)]
    if values.size == 0:
        return {"n": 0, "mean": float("nan"), **{k: float("nan") for k in SUMMARY_QUANTILES}, "max": float("nan")}
    quantiles = np.quantile(values, list(SUMMARY_QUANTILES.values()), method=QUANTILE_METHOD)
    return {"n": int(values.size), "mean": float(values.mean()),
            **{k: float(q) for k, q in zip(SUMMARY_QUANTILES, quantiles)}, "max": float(values.max())}


def paired_relative_difference(a, b, seed, resamples=2000, confidence=0.95):
    """Median over the draws of a/b - 1 (a and b paired: entry i of both is draw i), with a seeded
    percentile bootstrap interval over the draws. None when fewer than 2 pairs."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    keep = np.isfinite(a) & np.isfinite(b) & (b != 0.0)
    ratios = a[keep] / b[keep] - 1.0
    if ratios.size < 2:
        return None
    result = stats.bootstrap((ratios,), np.median, confidence_level=confidence, n_resamples=resamples,
                             method="percentile", random_state=np.random.default_rng(seed))
    return {"pairs": int(ratios.size), "median": float(np.median(ratios)),
            "low": float(result.confidence_interval.low), "high": float(result.confidence_interval.high)}


def reason_kind(reason):
    """What a divergence reason says went wrong, without its numbers and time: "roll |phi|",
    "controller failed", "non-finite state"."""
    return re.split(r" = | at t = ", reason, maxsplit=1)[0]
