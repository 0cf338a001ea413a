#!/usr/bin/python3
"""Plots the relative errors that `thetad approximation` writes with the thetad_plots package beside this file:

  MPLBACKEND=Agg /usr/bin/python3 scripts/plot_approximation.py OUT/approximation.csv docs/figures/approximation-error --format png

Needs Debian's python3-matplotlib (hence /usr/bin/python3). Errors: one line on stderr starting
with "plot_approximation.py:", exit status 1.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from thetad_plots import approximation  # noqa: E402  (found through the path above)

sys.exit(approximation.main(sys.argv))
