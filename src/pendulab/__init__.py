"""pendulab: the nonlinear simple pendulum and the numerical methods taught with it.

The heavy modules (numba kernels, scipy, matplotlib) are imported only when used.
"""
from ._version import __version__
from .errors import InputError, MissingExtraError, NumericalError, PendulabError
from .period import agm_period, period_digits, small_angle_period

__all__ = [
    "InputError",
    "MissingExtraError",
    "NumericalError",
    "PendulabError",
    "__version__",
    "agm_period",
    "period_digits",
    "small_angle_period",
]
