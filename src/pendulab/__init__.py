"""pendulab: the nonlinear simple pendulum and the numerical methods taught with it.

The heavy modules (numba kernels, scipy, matplotlib) are imported only when used.
"""
from .errors import InputError, NumericalError, PendulabError
from .period import agm_period, period_digits, small_angle_period

__all__ = [
    "InputError",
    "NumericalError",
    "PendulabError",
    "agm_period",
    "period_digits",
    "small_angle_period",
]
__version__ = "0.1.0"
