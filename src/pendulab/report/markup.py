"""Numbers as Typst markup: the forms of :mod:`pendulab.core.digits` (the one digit policy),
with a true minus sign and the power of ten as a superscript (no imports from the report)."""
from __future__ import annotations

import math
from typing import TypeGuard

from ..core import digits


def _sup(exp: int) -> str:
    return f"10#super[{'−' if exp < 0 else ''}{abs(exp)}]"


def typst(text: str) -> str:
    """Plain text of :mod:`pendulab.core.digits` (``-1.2e-5``, ``<= 2e-15``) as Typst
    (``−1.2 × 10^−5``, ``≤ 2 × 10^−15``)."""
    mant, exp = digits.split(text)
    mant = mant.replace("<=", "≤").replace("-", "−")
    return mant if exp is None else f"{mant} × {_sup(exp)}"


def _finite(x: float | None) -> TypeGuard[float]:
    return x is not None and math.isfinite(x)


def num(x: float | None, n: int = 10) -> str:
    """``x`` to ``n`` significant digits at most, trailing zeros dropped (``6.6``, not
    ``6.60000``: a value known exactly, such as a multiple of the step)."""
    return _g(x, n) if _finite(x) else "—"


def sci(x: float | None, n: int = 3) -> str:
    """``x`` in scientific notation, ``n`` significant digits."""
    return typst(digits.scientific(x, n)) if _finite(x) else "—"


def up(x: float, n: int = 4) -> str:
    """``|x|`` rounded *up* to ``n`` significant digits (a bound stays a bound)."""
    return typst(digits.bound(x, n)) if _finite(x) else "—"


def sci_up(x: float, n: int = 3) -> str:
    """``|x|`` rounded *up* to ``n`` significant digits in scientific notation (a bound)."""
    return typst(digits.bound(x, n, sci=True)) if _finite(x) else "—"


def err(x: float, error: float, most: int = 17) -> str:
    """``x`` with only the digits its ``error`` allows (:func:`pendulab.core.digits.with_error`)."""
    return typst(digits.with_error(x, error, most)) if _finite(x) else "—"


def eq(text: str) -> str:
    """``= text`` after a symbol, or ``text`` itself where it is a bound (``≤ 2 × 10^−15``, as
    :func:`err` prints a value its error swamps): ``|x_N - x_(N-1)| = 1.2 × 10^−8``."""
    return text if text.startswith("≤") else "= " + text


def shown(quantity: str, x: float, error: float | None = None) -> str:
    """``x`` in the form the digit policy gives ``quantity`` (:data:`pendulab.core.digits.POLICY`)."""
    return typst(digits.shown(quantity, x, error))


def sci_beside(x: float, limit: float, n: int = 2) -> str:
    """``x`` in scientific notation with the fewest digits (at least ``n``) whose value
    lies on the same side of ``limit`` as ``x``: a number printed beside "below ``limit``"
    never reads as ``limit`` itself."""
    for d in range(n, 18):
        shown_ = float(digits.scientific(x, d))
        if (shown_ < limit) == (x < limit) and (shown_ == limit) == (x == limit):
            return sci(x, d)
    return sci(x, 17)


def _g(x: float, n: int) -> str:
    """``x`` to ``n`` significant digits, the shortest text (``g``: no trailing zeros)."""
    text = f"{x:.{n}g}"
    if "e" in text:
        mant, exp = text.split("e")
        return typst(f"{mant}e{int(exp)}")
    return typst(text)


def significant(x: float | None, n: int) -> str:
    """``x`` to ``n`` significant digits, trailing zeros kept (a measured or computed value)."""
    return typst(digits.significant(x, n)) if _finite(x) else "—"


def fixed(x: float, decimals: int) -> str:
    """``x`` with ``decimals`` decimals, correctly rounded."""
    return digits.fixed(x, decimals).replace("-", "−")


def integer(n: int) -> str:
    return f"{n:d}"
