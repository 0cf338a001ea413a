"""Separating a logged signal into its trend and the noise on it, for signals the noise dominates.

With 5 % measurement and actuator noise at 1 kHz, a commanded input such as the collective pitch
fills its whole range sample to sample; drawn raw, the command the controller means is hidden.
Such a signal is drawn as its low-pass-filtered trend (2nd-order Butterworth, run forwards and
backwards so that it adds no lag) over a band of ±2 σ of the measured noise. Every caption that
uses it says so.

The noise is measured from the second differences of the samples, not from the residual to the
trend: white noise of standard deviation σ gives second differences of standard deviation σ√6,
while a signal smooth at the logging rate gives almost none, so fast but real dynamics (a step of
the command, in a flight without noise) are not mistaken for noise. σ is the median absolute
second difference over a sliding window, / (0.6745 √6) (the median absolute deviation of a normal
variable is 0.6745 σ): robust to the jumps of the command.
"""

import numpy as np
import pandas as pd
from scipy import signal as sp

CUTOFF_HZ = 2.0
NOISE_WINDOW_S = 0.5
# A signal counts as noise-dominated when its ±2 σ noise band is wider than this fraction of the
# trend's range: then a raw line would show the noise, not the trend.
DOMINANCE = 0.1
MAD_TO_SIGMA = 1.0 / (0.6745 * np.sqrt(6.0))


def sample_rate(t):
    return 1.0 / np.median(np.diff(t)) if len(t) > 1 else 0.0


def lowpass(t, y):
    """y without its content above CUTOFF_HZ (zero phase); y itself when too short to filter."""
    rate = sample_rate(t)
    if rate <= 2.5 * CUTOFF_HZ or len(y) < 16:
        return np.asarray(y, dtype=float)
    b, a = sp.butter(2, CUTOFF_HZ / (rate / 2))
    return sp.filtfilt(b, a, y)


def noise_sigma(t, y):
    """σ of the noise on y per sample, from the second differences in a window around it."""
    y = np.asarray(y, dtype=float)
    if len(y) < 3:
        return np.zeros(len(y))
    second = np.abs(np.diff(y, 2))
    second = np.concatenate([second[:1], second, second[-1:]])
    window = max(3, int(round(NOISE_WINDOW_S * sample_rate(t))))
    return MAD_TO_SIGMA * pd.Series(second).rolling(window, center=True, min_periods=1).median().to_numpy()


def split(t, y):
    """(trend, σ of the noise around it per sample)."""
    return lowpass(t, y), noise_sigma(t, y)


def dominated(t, y):
    """Whether the noise on y is wide against y's trend (the DOMINANCE criterion, on the median σ)."""
    trend, sigma = split(t, y)
    span = np.ptp(trend)
    width = 4 * np.median(sigma)
    return bool(width > DOMINANCE * span) if span > 0 else bool(width > 0)
