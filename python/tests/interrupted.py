"""Ctrl-C from outside: a child Python runs some work until SIGINT, which must raise
KeyboardInterrupt promptly."""

import os
import signal
import subprocess
import sys
import textwrap
import time

# The child: `setup`, then `work`, saying when the work starts and how it ended.
CHILD = """
import sys, time
import thetad
{setup}
print("started", flush=True)
try:
    {work}
    print("completed", flush=True)
except KeyboardInterrupt as stop:
    print("interrupted", time.monotonic(), stop, flush=True)
"""


def interrupt(setup, work, *arguments, after=1.0):
    """Runs `setup` then the statement `work` in a child Python (sys.argv[1:]: `arguments`), sends
    SIGINT `after` seconds into `work`, checks that its KeyboardInterrupt came within a second and
    returns the KeyboardInterrupt's message."""
    source = CHILD.format(setup=textwrap.dedent(setup), work=work)
    child = subprocess.Popen([sys.executable, "-c", source, *map(str, arguments)], stdout=subprocess.PIPE, text=True,
                             env=dict(os.environ))
    try:
        assert child.stdout.readline().strip() == "started"
        time.sleep(after)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        line = child.stdout.readline().split(maxsplit=2)
        assert child.wait(timeout=30) == 0
    finally:
        child.kill()
    assert line[0] == "interrupted", line
    assert float(line[1]) - sent < 1.0, f"KeyboardInterrupt {float(line[1]) - sent:.2f} s after SIGINT"
    return line[2]
