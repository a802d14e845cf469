"""Small validators: each checks one value and returns it (the scipy ``_ivp`` habit)."""
from __future__ import annotations

import math
from typing import Any

from .errors import InputError


def finite(name: str, value: Any) -> float:
    """Return ``value`` as a float, or raise if it is not a finite real number."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(name, value, "a finite real number") from None
    if not math.isfinite(x):
        raise InputError(name, value, "a finite real number")
    return x


def positive(name: str, value: Any) -> float:
    """A finite number > 0 (a length, a step, g)."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        x = math.nan
    if not (math.isfinite(x) and x > 0):
        raise InputError(name, value, "a finite number > 0")
    return x


def non_negative(name: str, value: Any) -> float:
    """A finite number >= 0 (a measurement error)."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        x = math.nan
    if not (math.isfinite(x) and x >= 0):
        raise InputError(name, value, "a finite number >= 0")
    return x


def amplitude(name: str, value: Any) -> float:
    """An amplitude in radians, ``0 <= alpha < pi`` (spec, Introduction)."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        x = math.nan
    if not (math.isfinite(x) and 0.0 <= x < math.pi):
        raise InputError(name, value, "an angle in [0, pi) rad")
    return x


def integer(name: str, value: Any, low: int, high: int | None = None) -> int:
    """An integer in ``[low, high]`` (``high=None``: no upper bound)."""
    ok = isinstance(value, int) and not isinstance(value, bool)
    if isinstance(value, float) and value.is_integer():
        value, ok = int(value), True
    if not ok or value < low or (high is not None and value > high):
        rng = f"an integer >= {low}" if high is None else f"an integer in [{low}, {high}]"
        raise InputError(name, value, rng)
    return int(value)


def time_span(t0: Any, t_max: Any, step: Any) -> tuple[float, float, float]:
    """Check ``t0 < t_max`` and ``0 < step < t_max - t0``; return them as floats."""
    t0 = finite("t0", t0)
    t_max = finite("t_max", t_max)
    step = positive("step", step)
    if not t_max > t0:
        raise InputError("t_max", t_max, f"> t0 = {t0:g}")
    if not step < t_max - t0:
        raise InputError("step", step, f"< t_max - t0 = {t_max - t0:g}")
    return t0, t_max, step
