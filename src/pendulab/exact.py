"""Numbers as the user wrote them.

``4pi/5``, ``45deg`` or ``2.0800838231`` are exact real numbers; their doubles are not.
:class:`Exact` keeps the exact value (a rational multiple of 1 or of pi) so that a
high-precision computation starts from what was written, and gives the double nearest
to it (correctly rounded) for the float path.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from fractions import Fraction

from .errors import InputError

_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
# "4pi/5", "4*pi/5", "pi/4", "-pi", "3pi", "0.5*pi", "pi*2/3"
_PI_FORM = re.compile(
    rf"^(?P<num>{_NUMBER})?\s*\*?\s*(?:π|pi)\s*(?:\*\s*(?P<mul>{_NUMBER}))?\s*(?:/\s*(?P<den>{_NUMBER}))?$",
    re.IGNORECASE,
)
_DEG_FORM = re.compile(rf"^(?P<num>{_NUMBER})\s*(?:deg|degrees?|°)$", re.IGNORECASE)
_RAD_FORM = re.compile(rf"^(?P<num>{_NUMBER})\s*(?:rad)?$", re.IGNORECASE)
_FRACTION_FORM = re.compile(rf"^(?P<num>{_NUMBER})\s*/\s*(?P<den>{_NUMBER})$")


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
            return float(self.coef)  # Fraction -> float is correctly rounded
        return float(self.mpf(40))

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


_EXPONENT = re.compile(r"[eE]([+-]?\d+)$")
#: Exponents beyond this are far outside the doubles; refusing them keeps ``Fraction``
#: from building a gigantic integer (``1e99999999`` would never finish).
_MAX_EXPONENT = 400
_MAX_DIGITS = 200


def _fraction(text: str) -> Fraction:
    """The exact value of a decimal literal such as ``9.80665`` or ``1e-3``."""
    m = _EXPONENT.search(text)
    if len(text) > _MAX_DIGITS or (m and abs(int(m.group(1))) > _MAX_EXPONENT):
        raise ValueError(text)
    return Fraction(text)


def parse_number(name: str, text: str) -> Exact:
    """Parse a plain real number or ratio, ``2.0800838231`` or ``1/3``, exactly."""
    s = str(text).strip()
    try:
        if m := _FRACTION_FORM.match(s):
            den = _fraction(m["den"])
            if den == 0:
                raise ZeroDivisionError
            return Exact(_fraction(m["num"]) / den, 0, s)
        if _RAD_FORM.match(s):
            return Exact(_fraction(s.rstrip("radRAD ").strip()), 0, s)
    except (ValueError, ZeroDivisionError):
        pass
    raise InputError(name, repr(text), "a number such as 3.5, 2e-3 or 1/3")


def parse_angle(name: str, text: str | float) -> Exact:
    """Parse an angle: ``0.785``, ``pi/4``, ``4pi/5``, ``4*pi/5``, ``45deg``, ``45°``.

    Returns the exact angle in radians. Range is not checked here (see
    :func:`pendulab._validate.amplitude`).
    """
    if isinstance(text, (int, float)):
        return Exact.of(text)
    s = str(text).strip().replace(" ", "")
    try:
        if m := _PI_FORM.match(s):
            coef = Fraction(1)
            if m["num"] is not None:
                coef *= _fraction(m["num"])
            if m["mul"] is not None:
                coef *= _fraction(m["mul"])
            if m["den"] is not None:
                coef /= _fraction(m["den"])
            return Exact(coef, 1, str(text).strip())
        if m := _DEG_FORM.match(s):
            return Exact(_fraction(m["num"]) / 180, 1, str(text).strip())
        return Exact(parse_number(name, s).coef, 0, str(text).strip())
    except (ValueError, ZeroDivisionError, InputError):
        pass
    raise InputError(name, repr(text), "an angle such as 0.785, pi/4, 4pi/5, 45deg or 45°")


def degrees(x: float) -> float:
    """Radians to degrees."""
    return math.degrees(x)
