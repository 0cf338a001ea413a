"""thetad from Python: the θ–D, SDRE and LQR controllers on the X-Cell helicopter model, at C++ speed.

The numerics (care, lqr, dare, dlqr, lyap), the model (Helicopter), the registered controllers (controller,
controllers), controllers written in Python (subclasses of Controller), flights (run, compare) and the
workflows (bench, optimal, campaign_run, tune) come from the C++ library through the extension module
thetad._thetad; plot and campaign_report draw with the shipped scripts; a plant written in Python derives
from Plant (thetad/plant.py). docs/python.md is the guide.
"""

import os as _os
import sys as _sys

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

# A plug-in resolves thetad's symbols against the module that loads it: the module's must be
# global (Python loads extension modules RTLD_LOCAL), as the thetad program exports its own.
_flags = _sys.getdlopenflags()
_sys.setdlopenflags(_flags | _os.RTLD_GLOBAL)
from ._thetad import (  # noqa: E402  (after the data folder is known)
    CareResult,
    Controller,
    DareResult,
    DesignDefaults,
    Error,
    Helicopter,
    Linearization,
    Optimality,
    Reference,
    RegisteredController,
    RunResult,
    Trim,
    __version__,
    bench,
    campaign_run,
    care,
    compare,
    comparison_table,
    controller,
    controllers,
    dare,
    demo,
    dlqr,
    input_names,
    linearize,
    load_plugin,
    lqr,
    lyap,
    optimal,
    plants,
    run,
    state_names,
    tune,
    uncertainty_draw,
)

_sys.setdlopenflags(_flags)
_thetad._load_plugins_from_environment()

from .campaigns import CampaignReport, campaign_report  # noqa: E402
from .figures import plot  # noqa: E402
from .plant import Plant  # noqa: E402

__all__ = [
    "CampaignReport", "CareResult", "Controller", "DareResult", "DesignDefaults", "Error", "Helicopter", "Linearization",
    "Optimality", "Plant", "Reference", "RegisteredController", "RunResult", "Trim", "bench", "campaign_report",
    "campaign_run", "care", "compare", "comparison_table", "controller", "controllers", "dare", "dlqr", "input_names", "linearize",
    "load_plugin", "lqr", "lyap", "optimal", "plants", "plot", "run", "state_names", "tune", "uncertainty_draw",
]
