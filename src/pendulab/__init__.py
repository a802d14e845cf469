"""pendulab: the nonlinear simple pendulum and the numerical methods taught with it.

The heavy modules (numba kernels, scipy, matplotlib) are imported only when used: the
period functions too (PEP 562), so that the command line starts, and handles Ctrl+C,
before numpy and numba load.
"""
from ._version import __version__
from .errors import InputError, MissingExtraError, NumericalError, PendulabError

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

_LAZY = ("agm_period", "period_digits", "small_angle_period")


def __getattr__(name: str) -> object:
    if name in _LAZY:
        from . import period

        return getattr(period, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
