#!/usr/bin/python3
"""Draws the certificates along flights (docs/reproduction.md) with the thetad_plots package beside this file:

  MPLBACKEND=Agg /usr/bin/python3 scripts/plot_certificates.py docs/figures/certificates \\
      "scenario I=out/certificates/scenario-1" "stress variant=out/certificates/stress" --format png

Needs Debian's python3-matplotlib and -pandas (hence /usr/bin/python3). Errors: one line on stderr
starting with "plot_certificates.py:", exit status 1.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from thetad_plots import certificates  # noqa: E402  (found through the path above)

sys.exit(certificates.main(sys.argv))
