"""Problem 1: ``g`` from a measured length and period, with its propagated error.

From the small-angle period ``T = 2 pi sqrt(l/g)`` (problem 1), ``g = 4 pi^2 l / T^2``.
Measured values ``l~``, ``T~`` with absolute errors at most ``dl``, ``dT`` give, to first
order (the general error-propagation formula, [1]_ chapter 1)::

    |e_g| <= |dg/dl| dl + |dg/dT| dT = (4 pi^2 / T^2) dl + (8 pi^2 l / T^3) dT,
    |e_g| / |g| <= dl / l + 2 dT / T.

Because ``g`` grows with ``l`` and falls with ``T``, the exact worst case over the box
``[l - dl, l + dl] x [T - dT, T + dT]`` is attained at its corners; it is reported too,
and the significant digits are counted with the larger of the two bounds, so they are
guaranteed, not only first-order.

Significant digits (the definition used in the course, [1]_ chapter 1): an approximation ``x~`` whose leading
digit has place value ``10^k`` (``k = floor(log10 |x~|)``) has ``n`` significant digits
when ``|x - x~| <= 0.5 * 10^(k - n + 1)``, i.e. the error is at most half a unit in the
``n``-th significant digit. ``n`` is the largest integer for which that holds.

References
----------
.. [1] H. Pina, *Métodos Numéricos*, McGraw-Hill, 1995 (and Escolar Editora, 2010).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import ROUND_HALF_UP, Decimal, localcontext
from fractions import Fraction

from ..core import validate as v
from ..core.errors import InputError
from .results import Result

#: Never claim more digits than a double carries.
MAX_DIGITS = 15


def gravity(length: float, period: float) -> float:
    """``g = 4 pi^2 l / T^2``, the small-angle period formula of problem 1 solved for ``g``."""
    return 4 * math.pi**2 * length / period**2


def abs_error_bound(length: float, length_error: float, period: float, period_error: float) -> float:
    """First-order absolute error bound of ``g``: ``(4 pi^2/T^2) dl + (8 pi^2 l/T^3) dT``."""
    return 4 * math.pi**2 / period**2 * length_error + 8 * math.pi**2 * length / period**3 * period_error


def rel_error_bound(length: float, length_error: float, period: float, period_error: float) -> float:
    """First-order relative error bound of ``g``: ``dl/l + 2 dT/T``."""
    return length_error / length + 2 * period_error / period


def leading_exponent(value: float) -> int:
    """``k = floor(log10 |value|)`` exactly, for a finite non-zero double.

    The decimal exponent of the leading digit of the double's exact value (``Decimal`` of a
    float is exact): ``math.log10`` rounds up just below a power of ten
    (``log10(99.99999999999999) == 2.0``) and would claim one digit too many.
    """
    return Decimal(value).adjusted()


def significant_digits(value: float, error: float, max_digits: int = MAX_DIGITS) -> int:
    """The number ``n`` of significant digits guaranteed for ``value`` by ``|error|``.

    The largest ``n`` with ``error <= 0.5 * 10^(k - n + 1)``, ``k = floor(log10|value|)``
    (module docstring), decided on the exact values of the doubles (``Fraction``), so a
    value just below a power of ten or an error on a half-unit tie is counted by the rule,
    not by the rounding of a logarithm. 0 when the error exceeds half a unit of the
    leading digit (or is not finite); ``max_digits`` when the error is 0.
    """
    if value == 0 or not math.isfinite(error):
        return 0
    if error <= 0:
        return max_digits
    k = leading_exponent(value)
    twice = 2 * Fraction(error)

    def holds(n: int) -> bool:  # error <= 0.5 * 10^(k - n + 1), exactly
        return twice <= Fraction(10) ** (k - n + 1)

    # A first guess from the exponent of the error, then the exact test decides.
    n = k + 1 - leading_exponent(2 * error if 2 * error < math.inf else error)
    n = max(0, min(n, max_digits))
    while n < max_digits and holds(n + 1):
        n += 1
    while n > 0 and not holds(n):
        n -= 1
    return n


def round_significant(value: float, digits: int) -> str:
    """``value`` rounded half away from zero to ``digits`` significant digits, as text.

    The exact value of the double is rounded (``Decimal(value)``), so ``0.125`` gives
    ``0.13``. A carry into a new leading digit keeps ``digits`` digits of the result:
    ``9.96`` to 2 digits is ``10``, not ``10.0``. Plain decimal notation (``12``,
    ``1000``, ``0.0012``), never E-notation, for a leading digit between ``10^-7`` and
    ``10^20``; beyond, scientific (``1.2E+25``). The digit count is stated with the text
    wherever it is shown, since ``10`` or ``1000`` does not say it.
    """
    if digits <= 0 or value == 0:
        return "0"
    d = Decimal(value)
    with localcontext() as ctx:
        ctx.prec = max(28, digits + 2)
        for _ in range(2):  # a second pass when rounding carried into a new leading digit
            q = d.quantize(Decimal(1).scaleb(d.adjusted() - digits + 1), rounding=ROUND_HALF_UP)
            if q.adjusted() == d.adjusted():
                break
            d = q
    if -7 <= q.adjusted() <= 20:
        return f"{q:f}"
    return str(q)


@dataclass(frozen=True, eq=False)
class GravityEstimate(Result):
    """``g`` from measured ``l`` and ``T``, with its error bounds (problem 1).

    Attributes
    ----------
    length, length_error : float
        ``l`` and its absolute error bound, m.
    measured_period, measured_period_error : float
        The measured ``T`` and its absolute error bound, s (glossary: not ``period``, the AGM's).
    g : float
        ``4 pi^2 l / T^2``, m/s^2.
    abs_error, rel_error : float
        First-order propagated bounds (1(a)).
    dg_dl, dg_dT : float
        The partial derivatives ``4 pi^2/T^2`` and ``-8 pi^2 l/T^3`` at the measured point.
    g_min, g_max : float
        The exact range of ``g`` over the error box (corners ``(l-dl, T+dT)``, ``(l+dl, T-dT)``).
    worst_error : float
        ``max(g_max - g, g - g_min)``: the exact worst-case error.
    error_bound : float
        ``max(abs_error, worst_error)``: the bound used to count digits.
    significant_digits : int
        Digits guaranteed by ``error_bound`` under the half-unit rule of the module (1(b)).
    g_text : str
        ``g`` rounded half away from zero to those digits.
    """

    length: float
    length_error: float
    measured_period: float
    measured_period_error: float
    g: float
    abs_error: float
    rel_error: float
    dg_dl: float
    dg_dT: float
    g_min: float
    g_max: float
    worst_error: float
    error_bound: float
    significant_digits: int
    g_text: str


def gravity_estimate(length: float, length_error: float, period: float, period_error: float) -> GravityEstimate:
    """``g`` and its propagated error from measured ``l +- dl`` (m) and ``T +- dT`` (s).

    Parameters
    ----------
    length : float
        ``l > 0``, m.
    length_error : float
        ``0 <= dl < l``, m.
    period : float
        ``T > 0``, s.
    period_error : float
        ``0 <= dT < T``, s.

    Returns
    -------
    GravityEstimate
    """
    length = v.positive("length", length)
    period = v.positive("period", period)
    length_error = v.non_negative("length_error", length_error)
    period_error = v.non_negative("period_error", period_error)
    if not length_error < length:
        raise InputError("length_error", length_error, f"< length = {length:g} m (so that the box holds positive lengths only)",
                         mentions=("length",))
    if not period_error < period:
        raise InputError("period_error", period_error, f"< period = {period:g} s (so that the box holds positive periods only)",
                         mentions=("period",))
    try:
        g = gravity(length, period)
        abs_err = abs_error_bound(length, length_error, period, period_error)
        rel_err = rel_error_bound(length, length_error, period, period_error)
        g_min = gravity(length - length_error, period + period_error)
        g_max = gravity(length + length_error, period - period_error)
        worst = max(g_max - g, g - g_min)
        bound = max(abs_err, worst)
        finite = all(math.isfinite(x) and x != 0 for x in (g, g_min, g_max)) and math.isfinite(bound)
    except (OverflowError, ZeroDivisionError):  # T**3 beyond the doubles, or T**2 below them
        finite = False
    if not finite:
        # Blame the input less like a laboratory pendulum's (1 m, 2 s).
        name = v.furthest(("period", period, 2.0), ("length", length, 1.0))
        value = period if name == "period" else length
        raise InputError(name, value, "such that g = 4 pi^2 l/T^2 and its error bounds are finite, "
                         "non-zero doubles (T^3 and l/T^2 within 1e-308..1e308)")
    n = significant_digits(g, bound)
    return GravityEstimate(
        length=length,
        length_error=length_error,
        measured_period=period,
        measured_period_error=period_error,
        g=g,
        abs_error=abs_err,
        rel_error=rel_err,
        dg_dl=4 * math.pi**2 / period**2,
        dg_dT=-8 * math.pi**2 * length / period**3,
        g_min=g_min,
        g_max=g_max,
        worst_error=worst,
        error_bound=bound,
        significant_digits=n,
        g_text=round_significant(g, n),
    )
