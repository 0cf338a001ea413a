#!/usr/bin/python3
"""What `thetad plot` runs: `plot_run.py MANIFEST.json` draws every figure of the runs the
manifest lists with the thetad_plots package beside this file (thetad_plots/run.py says what and
thetad_plots/results.py what the manifest holds). Needs Debian's python3-matplotlib, -pandas and
-scipy (run with /usr/bin/python3 and MPLBACKEND=Agg). Errors: one line on stderr starting with
"plot_run.py:", exit status 1.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from thetad_plots import run  # noqa: E402  (found through the path above)

sys.exit(run.main(sys.argv))
