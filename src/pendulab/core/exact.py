"""Numbers as the user wrote them.

``4pi/5``, ``45deg`` or ``2.0800838231`` are exact real numbers; their doubles are not.
:class:`Exact` keeps the exact value (a rational multiple of 1 or of pi) so that a
high-precision computation starts from what was written, and gives the double nearest
to it (correctly rounded) for the float path.
"""
from __future__ import annotations

import math
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from fractions import Fraction
from typing import Any


@dataclass(frozen=True)
class Exact:
    """The real number ``coef * pi**pi_power`` with a rational ``coef``.

    Attributes
    ----------
    coef : Fraction
        Exact rational coefficient.
    pi_power : int
        0 for a plain number, 1 for a multiple of pi.
    text : str
        What the user wrote, for messages and reports.
    """

    coef: Fraction
    pi_power: int = 0
    text: str = ""

    def __float__(self) -> float:
        if self.pi_power == 0:
            try:
                return float(self.coef)  # Fraction -> float is correctly rounded
            except OverflowError:  # beyond the largest double
                return math.inf if self.coef > 0 else -math.inf
        # coef * pi between bounds of pi at growing precision (Ziv): when both ends round
        # to the same double, so does the exact product (pi is irrational: it resolves).
        bits = 128
        while True:
            lo, hi = _pi_bounds(bits)
            ends = [self.coef * Fraction(b, 1 << bits) for b in (lo, hi)]
            try:
                a, b = float(min(ends)), float(max(ends))
            except OverflowError:  # beyond the largest double
                return math.inf if self.coef > 0 else -math.inf
            if a == b:
                return a
            bits *= 2  # pragma: no cover - coef pi within 2^-128 of a rounding boundary

    def mpf(self, dps: int):
        """The value as an ``mpmath.mpf`` at ``dps`` significant digits."""
        import mpmath

        with mpmath.workdps(dps + 10):
            v = mpmath.mpf(self.coef.numerator) / self.coef.denominator
            if self.pi_power:
                v = v * mpmath.pi**self.pi_power
        return +v

    def __str__(self) -> str:
        return self.text or str(float(self))

    @classmethod
    def of(cls, value: Exact | float | int) -> Exact:
        """Coerce a float (its exact binary value) or an int; text is parsed by
        :func:`pendulab.core.inputs.parse_number`."""
        if isinstance(value, Exact):
            return value
        return cls(Fraction(value), 0, repr(value))


def _pi_bounds(bits: int) -> tuple[int, int]:
    """Integers ``lo < hi`` with ``lo <= pi 2^bits <= hi``, by Machin's formula
    ``pi = 16 atan(1/5) - 4 atan(1/239)`` in fixed point with 20 guard bits.

    Each term of the two arctangent series is rounded down (an error below one unit), and
    the series stop below one unit: at most ``16 (n5 + 1) + 4 (n239 + 1)`` units in all,
    less than the ``64 (bits + 20)`` allowed for.
    """
    one = 1 << (bits + 20)

    def atan_inv(x: int) -> int:  # atan(1/x) = sum (-1)^k / ((2k + 1) x^(2k+1))
        total, power, k, x2 = 0, one // x, 0, x * x
        while power:
            term = power // (2 * k + 1)
            total += -term if k % 2 else term
            power //= x2
            k += 1
        return total

    v = 16 * atan_inv(5) - 4 * atan_inv(239)
    err = 64 * (bits + 20)
    return (v - err) >> 20, ((v + err) >> 20) + 1


def below_pi(x: Exact) -> bool:
    """``x < pi`` decided exactly: on the coefficient for a multiple of pi, else by Arb
    balls of growing precision (pi is irrational, so the comparison always resolves)."""
    if x.pi_power == 1:
        return x.coef < 1
    if x.coef <= 3 or x.coef >= 4:
        return x.coef <= 3
    from flint import arb, fmpq

    prec = 64
    with arb_precision(prec) as ctx:
        while True:
            ctx.prec = prec
            d = arb.pi() - arb(fmpq(x.coef.numerator, x.coef.denominator))
            if d > 0 or d < 0:
                return bool(d > 0)
            prec *= 2


_ARB_LOCK = threading.RLock()


@contextmanager
def arb_precision(prec: int) -> Iterator[Any]:
    """Arb's working precision (bits) is one global setting: set it under a lock, restore it."""
    from flint import ctx

    with _ARB_LOCK:
        old = ctx.prec
        ctx.prec = prec
        try:
            yield ctx
        finally:
            ctx.prec = old
