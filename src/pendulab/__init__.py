"""pendulab: the nonlinear simple pendulum and the numerical methods taught with it.

The functions a notebook needs, importable from here::

    from pendulab import agm_period, period_digits, simulate, estimate_period, problem1, to_frame

Each name loads its module on first use (PEP 562), so ``import pendulab`` imports neither
numpy, numba nor scipy, and the command line starts, and handles Ctrl+C, before they load.
Plots are in :mod:`pendulab.plots`.
"""
from __future__ import annotations

from .core.errors import InputError, MissingExtraError, NumericalError, PendulabError
from .core.extras import lazy
from .core.version import __version__

# ``typing`` is left unimported: its milliseconds come before the command line's entry point
# handles Ctrl+C (type checkers read the name TYPE_CHECKING as true).
TYPE_CHECKING = False
if TYPE_CHECKING:
    from .jobs.problems import problem1, problem2, problem3, problem4, problem5
    from .numerics.approximations import approximation_errors
    from .numerics.crossing import estimate_period
    from .numerics.group import group_length
    from .numerics.motion import exact_motion, global_error
    from .numerics.period import agm_period, period_digits, small_angle_period
    from .numerics.results import to_frame
    from .numerics.simulation import simulate

# name -> the module that defines it, imported on first use (PEP 562).
_WHERE = {
    "agm_period": "numerics.period",
    "period_digits": "numerics.period",
    "small_angle_period": "numerics.period",
    "simulate": "numerics.simulation",
    "estimate_period": "numerics.crossing",
    "group_length": "numerics.group",
    "exact_motion": "numerics.motion",
    "global_error": "numerics.motion",
    "approximation_errors": "numerics.approximations",
    "to_frame": "numerics.results",
    "problem1": "jobs.problems",
    "problem2": "jobs.problems",
    "problem3": "jobs.problems",
    "problem4": "jobs.problems",
    "problem5": "jobs.problems",
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
    "to_frame",
]

__getattr__, __dir__ = lazy(__name__, _WHERE, __all__)  # dir(pendulab): __all__, the public names
del lazy, TYPE_CHECKING, annotations
