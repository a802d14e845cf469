"""Small validators: each checks one value and returns it (the scipy ``_ivp`` habit)."""
from __future__ import annotations

import math
from decimal import ROUND_CEILING, ROUND_FLOOR, Decimal
from typing import Any

from .cases import G
from .errors import InputError
from .methods import cost_per_step, resolve


def finite(name: str, value: Any) -> float:
    """Return ``value`` as a float, or raise if it is not a finite real number."""
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError):
        raise InputError(name, value, "a finite real number") from None
    if not math.isfinite(x):
        raise InputError(name, value, "a finite real number")
    return x


#: The smallest positive normal double: below it a number keeps fewer than 53 bits.
TINY = 2.2250738585072014e-308
#: The longest period accepted, s: far beyond anything physical, and far enough from the
#: largest double that ``1.5 T + 4 h`` and ``T / M(1, cos(alpha/2))`` stay finite.
MAX_PERIOD = 1e300


def as_float(value: Any) -> float:
    """``float(value)``, or NaN where it has none (a string that is not a number, ``None``):
    each validator then refuses it with its own range."""
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        return math.nan


def positive(name: str, value: Any) -> float:
    """A finite number > 0 (a length, a step, g), not a subnormal double."""
    x = as_float(value)
    if not (math.isfinite(x) and x > 0):
        raise InputError(name, value, "a finite number > 0")
    if x < TINY:
        raise InputError(name, value, f"a finite number > 0, at least {TINY:.4g} (smaller doubles lose digits)")
    return x


def pendulum(length: Any, alpha: Any, g: Any) -> tuple[float, float, float]:
    """``(l, alpha, g)`` checked in that order: :func:`positive` ``length`` and ``g``, an
    :func:`amplitude` (the argument named ``amplitude`` in a message)."""
    return positive("length", length), amplitude("amplitude", alpha), positive("g", g)


def non_negative(name: str, value: Any) -> float:
    """A finite number >= 0 (a measurement error)."""
    x = as_float(value)
    if not (math.isfinite(x) and x >= 0):
        raise InputError(name, value, "a finite number >= 0")
    return x


def amplitude(name: str, value: Any) -> float:
    """An amplitude in radians, ``0 <= alpha < pi`` (spec, Introduction)."""
    x = as_float(value)
    if not (math.isfinite(x) and 0.0 <= x < math.pi):
        raise InputError(name, value, "an angle in [0, pi) rad")
    return x



def amplitudes(name: str, value: Any) -> Any:
    """:func:`amplitude` for a scalar, or a float array whose every element is in ``[0, pi)``
    (the first bad element is the one named)."""
    import numbers

    if isinstance(value, numbers.Real):
        return amplitude(name, value)
    import numpy as np

    if np.ndim(value) == 0:
        return amplitude(name, value)
    alpha = np.asarray(value, dtype=float)
    ok = np.isfinite(alpha) & (alpha >= 0) & (alpha < np.pi)
    if not np.all(ok):
        amplitude(name, alpha[~ok][0])
    return alpha

def integer(name: str, value: Any, low: int, high: int | None = None) -> int:
    """An integer in ``[low, high]`` (``high=None``: no upper bound)."""
    ok = isinstance(value, int) and not isinstance(value, bool)
    if isinstance(value, float) and value.is_integer():
        value, ok = int(value), True
    if not ok or value < low or (high is not None and value > high):
        rng = f"an integer >= {low}" if high is None else f"an integer in [{low}, {high}]"
        raise InputError(name, value, rng)
    return int(value)


def _span(t0: float) -> str:
    """``t_max - t0`` in words, ``t_max`` alone where ``t0 = 0`` (the usual case, and a CLI without ``--t0``)."""
    return "t_max" if t0 == 0 else "t_max - t0"


def time_span(t0: Any, t_max: Any, step: Any) -> tuple[float, float, float]:
    """Check ``t0 < t_max`` and ``0 < step < t_max - t0``; return them as floats."""
    t0 = finite("t0", t0)
    t_max = finite("t_max", t_max)
    step = positive("step", step)
    if not t_max > t0:
        raise InputError("t_max", t_max, f"> {t0:g} s" if t0 == 0 else f"> t0 = {t0:g} s", mentions=("t0",))
    if not step < t_max - t0:
        span = _span(t0)
        raise InputError("step", step, f"< {span} = {t_max - t0:g} s", mentions=("t_max", "t0"),
                         alternative=InputError("t_max", t_max, f"> {'' if t0 == 0 else 't0 + '}step = "
                                                f"{t0 + step:g} s", mentions=("t0", "step")))
    return t0, t_max, step


def too_much_work(name: str, value: Any, bound: str, most: float, need: float, what: str = "steps", *,
                  in_all: bool = False, hint: str = "", mentions: tuple[str, ...] = (),
                  alternative: InputError | None = None) -> InputError:
    """The one refusal of a run that would take more than ``most`` steps (or rows, or points).

    It reads ``NAME = VALUE is not allowed: must be BOUND (at most MOST WHAT [in all]; these
    need NEED[; HINT])``: the argument, its value, the range it must be in and the numbers
    that decide it. ``what`` names the unit, with the method where its cost weighs the
    limit (:func:`steps_of`).
    """
    tail = f"; {hint}" if hint else ""
    return InputError(name, value, f"{bound} (at most {most:.3g} {what}{' in all' if in_all else ''}; "
                                   f"these need {need:.3g}{tail})", mentions=mentions, alternative=alternative)


def bound_text(x: float, up: bool, digits: int = 3) -> str:
    """``x`` to ``digits`` significant digits, rounded away from the refused side.

    A lower bound is rounded up and an upper bound down, so that a value written as the
    message shows it is accepted (``t_max/1e6 = 0.119001`` shows as ``0.12``, not ``0.119``).
    """
    if not (math.isfinite(x) and x > 0):
        return f"{x:.{digits}g}"
    d = Decimal(x)
    q = d.quantize(Decimal(1).scaleb(d.adjusted() - digits + 1), rounding=ROUND_CEILING if up else ROUND_FLOOR)
    return f"{float(q):.{digits}g}"


def steps_of(method: Any) -> str:
    """``steps``, or ``steps of METHOD`` where a limit stated in steps of (3) is weighed by the method's cost."""
    m = resolve(method)
    return "steps" if m.name == "taylor2" else f"steps of {m.name}"


def furthest(*candidates: tuple[str, float, float]) -> str:
    """The name, of ``(name, value, ordinary)`` triples, whose value is furthest in decades from its ordinary one.

    A limit that two inputs share (the period ``2 pi sqrt(l/g)``, the steps ``t_max / h``)
    blames the one that looks least like an ordinary case: ``|log10(value / ordinary)|``
    largest, the first on a tie. Computed as a difference of logarithms, so a quotient
    that over- or underflows (``5e-324 / 2``) still compares. Values must be > 0.
    """
    return max(candidates, key=lambda c: abs(math.log10(c[1]) - math.log10(c[2])))[0]


def steps_within(name: str, t0: float, t_max: float, step: float, limit: int, what: str = "steps") -> int:
    """``N = Round((t_max - t0)/h)`` of (6), refused by arithmetic when it exceeds ``limit``.

    Checked on the float quotient before ``int()``: a huge ``t_max`` or a tiny ``step``
    is one clear error, never an ``OverflowError`` or a gigantic allocation later. The
    error blames ``name`` (the step); its alternative states the limit for ``t_max``.
    """
    q = (t_max - t0) / step
    if not q <= limit + 0.5:  # also catches inf and NaN
        raise step_limit(name, step, t0, t_max, limit, what)
    return int(round(q))


def step_limit(name: str, step: float, t0: float, t_max: float, limit: int, what: str = "steps",
               need: float | None = None, hint: str = "or a shorter t_max") -> InputError:
    """At most ``limit`` ``what`` of ``step`` over ``[t0, t_max]``: an error blaming ``name``
    (the step), with the same limit for ``t_max`` as its alternative; each hint names the
    other argument."""
    span = _span(t0)
    over = span if t0 == 0 else f"({span})"
    need = (t_max - t0) / step if need is None else need
    return too_much_work(
        name, step, f">= {over}/{limit:.3g} = {bound_text((t_max - t0) / limit, True)} s", limit, need, what,
        hint=hint, mentions=("t_max", "t0"),
        alternative=too_much_work("t_max", t_max, f"<= {bound_text(t0 + limit * step, False, 4)} s with {name} = {step:g} s",
                                  limit, need, what, hint=f"or a larger {name}", mentions=(name,)),
    )


def steps_for(method: Any, budget: float) -> int:
    """The most steps of ``method`` whose cost is ``budget`` steps of (3) (taylor2): every work
    limit is stated in steps of (3) and weighed by :func:`pendulab.core.methods.cost_per_step`."""
    return max(1, int(budget / cost_per_step(method)))


def work_within(name: str, value: Any, steps: float, method: Any, budget: float) -> float:
    """``steps`` steps of ``method`` (all the runs of one command or request together), refused
    naming ``name`` and ``value`` where they cost more than ``budget`` steps of (3)."""
    m = resolve(method)
    if not steps * cost_per_step(m) <= budget:  # also catches inf and NaN
        cost = "" if m.name == "taylor2" else f"a step of {m.name} costs {cost_per_step(m):.3g} of taylor2"
        raise too_much_work(name, value, "larger or fewer steps", steps_for(m, budget), steps, steps_of(m),
                            in_all=True, hint=cost)
    return steps


def sqrt_ratio(length: float, g: float) -> float:
    """``sqrt(l/g)``, also where ``l/g`` overflows or underflows but the root does not.

    ``sqrt(l/g)`` (two roundings) where the quotient is a normal double, else
    ``sqrt(l)/sqrt(g)``: ``l = 1e308, g = 1e-308`` gives ``1e308``, not ``inf``.
    """
    r = length / g
    if TINY <= r < math.inf:
        return math.sqrt(r)
    return math.sqrt(length) / math.sqrt(g)


def period_scale(length: float, g: float) -> float:
    """``2 pi sqrt(l/g)``, refused naming ``length`` or ``g`` beyond :data:`MAX_PERIOD`."""
    t0 = 2 * math.pi * sqrt_ratio(length, g)
    if not t0 <= MAX_PERIOD:
        q = MAX_PERIOD / (2 * math.pi)  # products, not q**2: a float product overflows to inf, ** raises
        if furthest(("length", length, 1.0), ("g", g, G)) == "length":  # from an ordinary pendulum
            limit = q * (q * g)
            raise InputError("length", length, f"<= {limit:.3g} m for g = {g:g} (period 2 pi sqrt(l/g) <= {MAX_PERIOD:g} s)")
        limit = length / q / q
        raise InputError("g", g, f">= {limit:.3g} m/s^2 for length = {length:g} (period 2 pi sqrt(l/g) <= {MAX_PERIOD:g} s)")
    return t0
