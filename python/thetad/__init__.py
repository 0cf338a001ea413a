"""thetad from Python: the θ–D, SDRE and LQR controllers on the X-Cell helicopter model, at C++ speed.

The numerics (care, lqr, dare, dlqr, lyap), the model (Helicopter), the registered controllers (controller,
controllers), controllers written in Python (subclasses of Controller), flights (run, compare) and
tuning (tune) come from the C++ library through the extension module thetad._thetad. docs/python.md is the guide.
"""

import os as _os

from . import _layout


def _point_at_installed_data():
    # An installed package finds the shipped scenarios in the prefix's share/thetad, which the
    # library locates from its own binary only when it is the thetad program; a build tree's
    # module finds them in its source tree. THETAD_DATA_DIR, when set, wins (docs/python.md).
    here = _os.path.dirname(_os.path.abspath(__file__))
    data = _os.path.normpath(_os.path.join(here, _layout.DATA_FROM_PACKAGE))
    if _os.path.isdir(_os.path.join(data, "scenarios")):
        _os.environ.setdefault("THETAD_DATA_DIR", data)


_point_at_installed_data()

from ._thetad import (  # noqa: E402  (after the data folder is known)
    CareResult,
    Controller,
    DareResult,
    DesignDefaults,
    Error,
    Helicopter,
    Linearization,
    Reference,
    RegisteredController,
    RunResult,
    Trim,
    __version__,
    care,
    compare,
    comparison_table,
    controller,
    controllers,
    dare,
    dlqr,
    input_names,
    linearize,
    lqr,
    lyap,
    run,
    state_names,
    tune,
    uncertainty_draw,
)

__all__ = [
    "CareResult", "Controller", "DareResult", "DesignDefaults", "Error", "Helicopter", "Linearization", "Reference",
    "RegisteredController", "RunResult", "Trim", "care", "compare", "comparison_table", "controller", "controllers",
    "dare", "dlqr", "input_names", "linearize", "lqr", "lyap", "run", "state_names", "tune", "uncertainty_draw",
]
