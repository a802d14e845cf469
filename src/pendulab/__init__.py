"""pendulab: the nonlinear simple pendulum and the numerical methods taught with it.

The functions a notebook needs, importable from here::

    from pendulab import agm_period, period_digits, simulate, estimate_period, problem1

Each name loads its module on first use (PEP 562), so ``import pendulab`` imports neither
numpy, numba nor scipy, and the command line starts, and handles Ctrl+C, before they load.
Plots are in :mod:`pendulab.plots`.
"""
from __future__ import annotations

from ._extras import lazy
from ._version import __version__
from .errors import InputError, MissingExtraError, NumericalError, PendulabError

# ``typing`` is left unimported: its milliseconds come before the command line's entry point
# handles Ctrl+C (type checkers read the name TYPE_CHECKING as true).
TYPE_CHECKING = False
if TYPE_CHECKING:
    from .approximations import approximation_errors
    from .crossing import estimate_period
    from .group import group_length
    from .motion import exact_motion, global_error
    from .period import agm_period, period_digits, small_angle_period
    from .problems import problem1, problem2, problem3, problem4, problem5
    from .taylor import simulate

# name -> the module that defines it, imported on first use (PEP 562).
_WHERE = {
    "agm_period": "period",
    "period_digits": "period",
    "small_angle_period": "period",
    "simulate": "taylor",
    "estimate_period": "crossing",
    "group_length": "group",
    "exact_motion": "motion",
    "global_error": "motion",
    "approximation_errors": "approximations",
    "problem1": "problems",
    "problem2": "problems",
    "problem3": "problems",
    "problem4": "problems",
    "problem5": "problems",
}

__all__ = [
    "InputError",
    "MissingExtraError",
    "NumericalError",
    "PendulabError",
    "__version__",
    "agm_period",
    "approximation_errors",
    "estimate_period",
    "exact_motion",
    "global_error",
    "group_length",
    "period_digits",
    "problem1",
    "problem2",
    "problem3",
    "problem4",
    "problem5",
    "simulate",
    "small_angle_period",
]

__getattr__, __dir__ = lazy(__name__, _WHERE, __all__)
