"""Numbers as the user wrote them.

``4pi/5``, ``45deg`` or ``2.0800838231`` are exact real numbers; their doubles are not.
:class:`Exact` keeps the exact value (a rational multiple of 1 or of pi) so that a
high-precision computation starts from what was written, and gives the double nearest
to it (correctly rounded) for the float path.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction


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
        return float(self.mpf(40))  # mpmath rounds an overflow to +-inf

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
    def of(cls, value: Exact | float | int | str) -> Exact:
        """Coerce a float (its exact binary value), an int or a string (:func:`parse_number`)."""
        if isinstance(value, Exact):
            return value
        if isinstance(value, str):
            return parse_number("value", value)
        return cls(Fraction(value), 0, repr(value))


def parse_number(name: str, text: str) -> Exact:
    """Parse a plain real number or ratio, ``2.0800838231`` or ``1/3``, exactly.

    The grammar and its limits are :func:`pendulab.inputs.real`'s.
    """
    from .inputs import real

    return real(name, text)


def parse_angle(name: str, text: str | float) -> Exact:
    """Parse an angle: ``0.785``, ``pi/4``, ``4pi/5``, ``4*pi/5``, ``45deg``, ``45°``.

    Returns the exact angle in radians; the range is not checked here (see
    :func:`pendulab.inputs.angle`, which does).
    """
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return Exact.of(text)
    from .inputs import angle_value

    return angle_value(name, text)
