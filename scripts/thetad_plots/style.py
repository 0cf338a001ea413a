"""The one look of every thetad figure: colours, line styles, sizes, fonts and file output.

Small on purpose; everything that draws a thetad figure (`thetad plot`, the benchmark report, the
tuning plot, campaign reports) uses these and nothing else for its look:

    from thetad_plots import style
    style.apply()                                   # fonts and rcParams, once per process
    fig, ax = plt.subplots(figsize=style.size(style.COLUMN, 0.7))
    for label in labels:
        ax.plot(t, y[label], **style.line(label, labels))
    ax.plot(t, reference, **style.REFERENCE)
    style.save(fig, "out/position", ["png", "pdf"])  # out/position.png, out/position.pdf

Colours are the Okabe–Ito palette (distinguishable with the common colour-vision deficiencies);
every controller also has its own dash pattern and marker, so overlays stay readable in grey
print. The registered controllers have fixed styles; any other label gets a style from the
remaining slots chosen by a hash of the label (stable for a set of labels; two labels of one
figure never share a slot). The reference (command) is always black and dashed, a colour no
controller uses. Sizes are for a journal page: COLUMN is a single column (8.5 cm), PAGE the full
text width (17.6 cm); fonts are 8 pt at that size, so a figure pasted at its own width reads
like the paper's text.
"""

import argparse
import os
import sys
import zlib
from dataclasses import dataclass

import matplotlib

matplotlib.use(os.environ.get("MPLBACKEND", "Agg"))
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
from matplotlib.layout_engine import ConstrainedLayoutEngine  # noqa: E402

from .results import PlotError  # noqa: E402

CM = 1 / 2.54
COLUMN = 8.5 * CM
PAGE = 17.6 * CM
FORMATS = ("png", "pdf", "svg")


@dataclass(frozen=True)
class Look:
    colour: str
    dashes: tuple  # matplotlib dash pattern (offset, (on, off, ...)); (0, ()) is solid
    marker: str


# Okabe & Ito (2008), "Color universal design": the colours besides black and yellow.
ORANGE, SKY_BLUE, GREEN, BLUE, VERMILLION, PURPLE = (
    "#E69F00", "#56B4E9", "#009E73", "#0072B2", "#D55E00", "#CC79A7")

KNOWN = {
    "theta-d": Look(BLUE, (0, ()), "o"),
    "sdre": Look(VERMILLION, (0, (5, 2)), "s"),
    "lqr": Look(GREEN, (0, (5, 1.5, 1, 1.5)), "^"),
    "lqr-scheduled": Look(PURPLE, (0, (1, 1.2)), "D"),
    "example-pid": Look(ORANGE, (0, (3, 1, 1, 1, 1, 1)), "v"),
}
# Slots for other labels: sky blue, then the palette again with other dashes and markers (Okabe–Ito's
# yellow is too faint on white for a line).
SPARE = [
    Look(SKY_BLUE, (0, (8, 2)), "P"),
    Look(BLUE, (0, (2, 2)), "X"),
    Look(ORANGE, (0, (8, 2, 2, 2)), "<"),
    Look(GREEN, (0, (1, 3)), ">"),
    Look(PURPLE, (0, (6, 2, 1, 2, 1, 2)), "h"),
    Look(VERMILLION, (0, (1, 2, 4, 2)), "*"),
]

REFERENCE = {"color": "black", "linestyle": (0, (4, 2)), "linewidth": 0.9, "label": "command", "zorder": 50}


def apply():
    """rcParams for print: 8 pt text (7 pt ticks and legends), thin frames, text kept as text in
    SVG and as TrueType in PDF so journals can re-typeset and search it."""
    plt.rcParams.update({
        "font.size": 8, "axes.titlesize": 8, "axes.labelsize": 8, "xtick.labelsize": 7,
        "ytick.labelsize": 7, "legend.fontsize": 7, "figure.titlesize": 8.5,
        "axes.linewidth": 0.6, "grid.linewidth": 0.4, "grid.alpha": 0.5, "lines.linewidth": 1.0,
        "xtick.major.width": 0.6, "ytick.major.width": 0.6, "legend.frameon": False,
        "savefig.bbox": "tight", "savefig.pad_inches": 0.02, "svg.fonttype": "none", "pdf.fonttype": 42,
        "axes.grid": True, "figure.constrained_layout.use": True,
    })


def looks(labels):
    """{label: Look} for the labels of one figure: fixed for the registered controllers, a spare
    slot for any other: the first, from a hash of the label on, whose colour the figure does not
    show yet, else whose look it does not; more labels than slots share them."""
    chosen = {label: KNOWN[label] for label in labels if label in KNOWN}
    # In sorted order, so that the slots do not depend on the order the labels come in.
    for label in sorted(set(labels) - set(chosen)):
        taken = set(chosen.values())
        colours = {look.colour for look in taken}
        start = zlib.crc32(label.encode()) % len(SPARE)
        order = [SPARE[(start + k) % len(SPARE)] for k in range(len(SPARE))]
        chosen[label] = next((look for look in order if look.colour not in colours),
                             next((look for look in order if look not in taken), order[0]))
    return {label: chosen[label] for label in labels}


def line(label, labels, rank=None, samples=None):
    """Keyword arguments for Axes.plot of `label`'s line in a figure of `labels`.

    Lines coincide where controllers agree; drawn widest first and narrower on top (`rank`: the
    label's position in `labels` unless given), every line shows around or through the ones above
    it. `samples`: the line's length, to put about 8 markers on it (none if not given)."""
    look = looks(labels)[label]
    rank = labels.index(label) if rank is None else rank
    kwargs = {"color": look.colour, "linestyle": look.dashes, "label": label, "alpha": 0.9,
              "linewidth": 1.9 - 1.1 * rank / max(1, len(labels) - 1), "zorder": 10 + rank}
    if samples:
        kwargs.update(marker=look.marker, markersize=3.5, markevery=(rank * samples // (8 * len(labels)) % samples,
                                                                     max(1, samples // 8)))
    return kwargs


def size(width, aspect):
    """(width, height) in inches for a figure `width` wide (COLUMN or PAGE) of height/width `aspect`."""
    return (width, width * aspect)


def save(fig, stem, formats, dpi=300):
    """Writes fig as stem.FORMAT for each of `formats` (png, pdf, svg) and closes it; the paths."""
    unknown = [f for f in formats if f not in FORMATS]
    if unknown:
        raise ValueError(f"unknown figure format {', '.join(unknown)} (known: {', '.join(FORMATS)})")
    paths = []
    # A figure placed by hand (no layout engine) keeps none from one format to the next: saving
    # tight, matplotlib 3.6 restores "no engine" as the style's default, constrained, which then
    # warns that it has no grid to lay out.
    constrained = isinstance(fig.get_layout_engine(), ConstrainedLayoutEngine)
    with plt.rc_context({"figure.constrained_layout.use": constrained}):
        for fmt in formats:
            path = f"{stem}.{fmt}"
            fig.savefig(path, dpi=dpi)
            paths.append(path)
    plt.close(fig)
    return paths


def add_format_option(parser):
    """The --format option of every figure command: one or more of png, pdf, svg."""
    parser.add_argument("--format", dest="formats", default="png", type=lambda s: s.split(","),
                        help="comma-separated output formats: png, pdf, svg (default png)")


def figure_command(argv, prog, description, source_help, read, draw):
    """The command of a one-figure script: `PROG SOURCE OUT_STEM [--format png,pdf,svg]` draws
    draw(*read(SOURCE)) and saves it (an extension on OUT_STEM is dropped). 0, or 1 after one
    line "PROG: error: ..." on stderr."""
    parser = argparse.ArgumentParser(prog=prog, description=description)
    parser.add_argument("source", help=source_help)
    parser.add_argument("out", help="output path without extension (an extension is dropped)")
    add_format_option(parser)
    arguments = parser.parse_args(argv[1:])
    try:
        apply()
        stem = arguments.out.rsplit(".", 1)[0] if arguments.out.endswith(FORMATS) else arguments.out
        save(draw(*read(arguments.source)), stem, arguments.formats, dpi=200)
    except (PlotError, ValueError) as e:
        print(f"{prog}: error: {e}", file=sys.stderr)
        return 1
    return 0
