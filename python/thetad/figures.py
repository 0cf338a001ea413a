"""thetad.plot: the figures `thetad plot` draws, for runs in memory or a folder of result files."""

import os
import tempfile

from . import _thetad


def plot(runs, out, formats=("png",), dpi=150, baseline=None):
    """Draws the paper's figures (Figs. 2-17 kinds) and the comparison figures of `runs` into the
    folder `out`, the controllers overlaid, in thetad's style; returns the files written.

    runs: a list of RunResult (flown with their logs, not summary_only), or a folder written by
    `thetad compare`, `thetad run` or RunResult.write. formats: png, svg, pdf. baseline: the label of
    the run the difference panels compare with (default: the first). The figures move into `out`
    only once all are drawn: a failure leaves `out` as it was.
    """
    formats = [formats] if isinstance(formats, str) else list(formats)
    if isinstance(runs, (str, os.PathLike)):
        return [str(p) for p in _thetad._draw_figures(os.fspath(runs), os.fspath(out), formats, dpi, baseline or "")]
    runs = list(runs)
    if not runs:
        raise ValueError("plot: no runs")
    with tempfile.TemporaryDirectory(prefix="thetad-plot-") as folder:
        for run in runs:
            run.write(folder)
        return [str(p) for p in _thetad._draw_figures(folder, os.fspath(out), formats, dpi, baseline or "")]
