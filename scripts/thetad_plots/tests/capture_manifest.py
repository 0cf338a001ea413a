"""A stand-in for plot_run.py that `thetad plot --script` runs in the tests: it keeps the manifest
thetad wrote (at $THETAD_TEST_MANIFEST) and draws one placeholder file so that thetad is content."""

import os
import shutil
import sys

shutil.copyfile(sys.argv[1], os.environ["THETAD_TEST_MANIFEST"])
with open(os.path.join(os.path.dirname(sys.argv[1]), "placeholder.txt"), "w") as f:
    f.write("manifest captured\n")
