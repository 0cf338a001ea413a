"""thetad.Plant: the base of a plant written in Python, flown by the C++ simulator and controllers like a plant
in C++ (docs/python.md, "A plant written in Python")."""

from . import _thetad


class Plant:
    """A plant in state-dependent-coefficient form, ẋ = f(x, u) = F(x; u) x + B(x; u) u exactly.

    A subclass defines
      state_dim, input_dim     ints, n and m
      f(self, x, u)            ẋ (n,) for x (n,) and u (m,)
      sdc(self, x, u)          (F (n, n), B (n, m)); u is where F and B are taken, which matters only
                               with sdc_depends_on_input
    and may define
      jacobian(self, x, u)     (df/dx (n, n), df/du (n, m)); None: thetad.optimal takes central differences
      state_names, input_names n and m names, each "name" or ("name", "unit"): the log's columns
      initial_state            (n,): where run(plant=...) starts when it is given no initial_state
      sdc_depends_on_input     True when F or B change with u (the controllers then iterate to the fixed point)
      design_defaults(self)    (diag Q (n,), diag R (m,), u0 (m,)), each None for its default (ones, ones, zeros)

    They are read when a flight starts; then f, sdc and jacobian are called with float64 arrays (copies).
    A plant in Python is slower than one in C++ and allocates at every call (docs/python.md).
    """

    state_dim = None
    input_dim = None
    jacobian = None
    state_names = None
    input_names = None
    initial_state = None
    sdc_depends_on_input = False

    def design_defaults(self):
        return None

    def sdc_residual(self, x, u=None):
        """max |F(x; u) x + B(x; u) u − f(x, u)| / max(1, max |f(x, u)|): the SDC identity's error at (x, u), 0 up
        to rounding for an exact factorization. u: the design input u0 when None. The plant's own checks apply:
        a wrong shape or a NaN raises thetad.Error naming the method."""
        return _thetad._sdc_residual(self, x, u)
