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


def up(x: float, digits: int = 4) -> str:
    """``|x|`` rounded *up* to ``digits`` significant digits, as :func:`num` writes it: a bound
    stays a bound (0.0273622 -> 0.02737). Decided on the double's exact decimal value."""
    from decimal import ROUND_CEILING, Decimal

    d = abs(Decimal(x))
    if d == 0 or not d.is_finite():
        return num(abs(x), digits)
    q = Decimal(1).scaleb(d.adjusted() - digits + 1)
    r = d.quantize(q, rounding=ROUND_CEILING)
    if r.adjusted() > d.adjusted():  # 9.9996 -> 10.00: one digit fewer after the carry
        r = r.quantize(q.scaleb(1), rounding=ROUND_CEILING)
    if -5 <= r.adjusted() < digits:
        return format(r, "f")
    mant, exp = f"{r:E}".split("E")
    return f"{mant} × {_sup(int(exp))}"


def sci_up(x: float, digits: int = 3) -> str:
    """``|x|`` rounded *up* to ``digits`` significant digits in scientific notation (a bound)."""
    from decimal import ROUND_CEILING, Decimal

    d = abs(Decimal(x))
    if d == 0 or not d.is_finite():
        return sci(abs(x), digits)
    q = Decimal(1).scaleb(d.adjusted() - digits + 1)
    r = d.quantize(q, rounding=ROUND_CEILING)
    if r.adjusted() > d.adjusted():
        r = r.quantize(q.scaleb(1), rounding=ROUND_CEILING)
    mant, exp = f"{r:.{digits - 1}E}".split("E")
    return f"{mant} × {_sup(int(exp))}"


def sci_beside(x: float, limit: float, digits: int = 2) -> str:
    """``x`` in scientific notation with the fewest digits (at least ``digits``) whose value
    lies on the same side of ``limit`` as ``x``: a number printed beside "below ``limit``"
    never reads as ``limit`` itself."""
    for d in range(digits, 18):
        shown = float(f"{x:.{d - 1}e}")
        if (shown < limit) == (x < limit) and (shown == limit) == (x == limit):
            return sci(x, d)
    return sci(x, 17)


def distinct(a: float, b: float, digits: int = 16) -> tuple[str, str]:
    """``a`` and ``b`` with the fewest significant digits (at least ``digits``, at most 17)
    from which each reads back as its own double: two different doubles never print the
    same digits."""
    for d in range(digits, 17):
        if float(f"{a:.{d}g}") == a and float(f"{b:.{d}g}") == b:
            return num(a, d), num(b, d)
    return num(a, 17), num(b, 17)


def fixed(x: float, decimals: int) -> str:
    """``x`` with ``decimals`` decimals (the rounding of ``format``: half to even on the double)."""
    return f"{x:.{decimals}f}".replace("-", "−")


def integer(n: int) -> str:
    return f"{n:d}"
