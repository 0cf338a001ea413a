#!/usr/bin/python3
"""Plots the σmax curves that `thetad tune` writes with the thetad_plots package beside this file:

  MPLBACKEND=Agg /usr/bin/python3 scripts/plot_tuning.py OUT/sigma-curves.csv docs/figures/tuning-sigma --format png

Needs Debian's python3-matplotlib (hence /usr/bin/python3). Errors: one line on stderr starting
with "plot_tuning.py:", exit status 1.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from thetad_plots import tuning  # noqa: E402  (found through the path above)

sys.exit(tuning.main(sys.argv))
