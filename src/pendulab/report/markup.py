"""Numbers as Typst markup: the report's only formatting helpers (no imports from the report)."""
from __future__ import annotations

import math


def _sup(exp: int) -> str:
    return f"10#super[{'−' if exp < 0 else ''}{abs(exp)}]"


def num(x: float | None, digits: int = 10) -> str:
    """``x`` to ``digits`` significant digits as Typst markup (``1.2 × 10^-5`` when tiny)."""
    if x is None or not math.isfinite(x):
        return "—"
    s = f"{x:.{digits}g}"
    if "e" in s:
        mant, exp = s.split("e")
        return f"{mant} × {_sup(int(exp))}"
    return s.replace("-", "−")


def sci(x: float | None, digits: int = 3) -> str:
    """``x`` in scientific notation, ``digits`` significant digits."""
    if x is None or not math.isfinite(x):
        return "—"
    if x == 0:
        return "0"
    mant, exp = f"{x:.{digits - 1}e}".split("e")
    return f"{mant.replace('-', '−')} × {_sup(int(exp))}"


def sci_mp(x, digits: int = 2) -> str:
    """An ``mpmath.mpf`` in scientific notation: its exponent may be far below a double's."""
    import mpmath

    if x == 0:
        return "0"
    with mpmath.workdps(max(30, digits + 10)):
        exp = int(mpmath.floor(mpmath.log10(abs(x))))
        mant = float(x / mpmath.mpf(10) ** exp)  # in [1, 10)
    text = f"{mant:.{digits - 1}f}"
    if text.lstrip("-").startswith("10"):  # 9.96 rounds to 10.0
        exp += 1
        text = f"{mant / 10:.{digits - 1}f}"
    return f"{text.replace('-', '−')} × {_sup(exp)}"


def fixed(x: float, decimals: int) -> str:
    """``x`` with ``decimals`` decimals (the rounding of ``format``: half to even on the double)."""
    return f"{x:.{decimals}f}".replace("-", "−")


def integer(n: int) -> str:
    return f"{n:d}"
