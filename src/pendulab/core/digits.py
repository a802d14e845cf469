"""The digit policy: one printed form per quantity, and only the digits a number's error allows.

Every presenter (the report, the key's PDF, the CLI) prints a number of the coursework through
:func:`shown` (by the quantity's name in :data:`POLICY`) or through the form functions below;
the result is plain text (``1.23e-5``, ``−`` never used), which a presenter may dress
(:mod:`pendulab.report.markup` writes the power of ten as Typst). ``docs/report.md`` has the
table of :data:`POLICY` (a test keeps the two the same).

A number printed with its last digit in the place ``10^q`` is *right* when it differs from the
true value by less than one unit of that place: :func:`with_error` keeps the places down to the
first ``q`` with ``error <= 0.5 10^q``, so ``|printed - true| <= error + 0.5 10^q <= 10^q``.
Every decision is made on the double's exact decimal value (:class:`decimal.Decimal`), never
on an already rounded product.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import ROUND_CEILING, ROUND_HALF_EVEN, Context, Decimal

__all__ = ["FORMS", "ORDER_ONE", "POLICY", "Form", "bound", "distance_of", "estimate_of", "fixed", "noise_bound", "place", "rounding_noise", "scientific",
           "shown", "significant", "split", "with_error"]

#: The kinds of form: ``fixed`` (``digits`` decimals, the tables' columns), ``significant``
#: (``digits`` significant digits as a plain decimal: order-1 values), ``scientific``
#: (``digits`` significant digits times a power of ten: errors and small differences),
#: ``bound`` (``digits`` significant digits rounded *up*: a bound stays a bound), ``error``
#: (the digits the quantity's error allows, :func:`with_error`), ``integer``.
FORMS = ("fixed", "significant", "scientific", "bound", "error", "integer")
#: Plain decimals for magnitudes in [10^-3, 10^6); beyond, scientific notation.
PLAIN = (Decimal("1e-3"), Decimal("1e6"))
#: The scientific forms (``scientific``, a ``bound`` asked for as scientific) print an
#: order-1 value, ``|x|`` in [0.1, 1000), as a plain decimal with the same significant digits
#: (``0.880``, not ``8.80e-1``); beyond, a power of ten.
ORDER_ONE = (Decimal("0.1"), Decimal("1e3"))
#: Room for every digit of a double's exact decimal value (at most 767 significant digits).
_EXACT = Context(prec=1100, Emin=-2000, Emax=2000)


@dataclass(frozen=True)
class Form:
    """How one quantity is printed: ``kind`` (one of :data:`FORMS`) and ``digits`` (decimals
    for ``fixed``, significant digits for the others, the most shown for ``error``)."""

    kind: str
    digits: int = 0

    def __post_init__(self) -> None:
        if self.kind not in FORMS:
            raise ValueError(f"kind = {self.kind!r}: one of {', '.join(FORMS)}")


#: One form per quantity the coursework prints (the names of ``docs/glossary.md`` where it
#: has one; the question where the quantity appears after the dot).
POLICY: dict[str, Form] = {
    # problem 1: the measured inputs as given, g from them, the propagated bounds
    "p1.g": Form("significant", 10),
    "p1.derivative": Form("significant", 8),
    "p1.g_range": Form("significant", 8),
    "p1.error_bound": Form("bound", 4),
    # problem 2: Newton's iterates (their digits from the rounding level delta), steps, quotients
    "p2.iterate": Form("error", 16),
    "p2.residual": Form("error", 3),
    "p2.step": Form("error", 3),
    "p2.error_estimate": Form("scientific", 2),
    "p2.quotient": Form("error", 17),
    "p2.constant": Form("significant", 10),
    "p2.relative_rounding": Form("bound", 1),
    # problem 3: the simulation's values (digits from their rounding), periods and errors
    "p3.state": Form("error", 12),
    "t_hat": Form("significant", 15),
    "estimate": Form("significant", 12),
    "error": Form("scientific", 3),
    "order": Form("fixed", 2),
    "p3.coefficient": Form("error", 10),
    "p3.error_estimate": Form("error", 3),
    # problem 4: the normal equations to 6 decimals as the coursework asks, the coefficients
    "p4.normal": Form("fixed", 6),
    "p4.coefficient": Form("significant", 10),
    "p4.deviation": Form("scientific", 4),
    # problem 5: the period by S_n (digits from its rounding error), the rate
    "p5.estimate": Form("error", 16),
    "p5.rate": Form("fixed", 4),
}


def _decimal(x: float) -> Decimal:
    d = Decimal(x)
    if not d.is_finite():
        raise ValueError(f"x = {x!r}: a finite number")
    return d


def split(text: str) -> tuple[str, int | None]:
    """``"1.23e-5"`` -> ``("1.23", -5)``; ``"0.25"`` -> ``("0.25", None)``: for a presenter
    that writes the power of ten its own way."""
    if "e" in text:
        mant, exp = text.split("e")
        return mant, int(exp)
    return text, None


def _text(d: Decimal, q: int, sci: bool | None = None) -> str:
    """``d``, already a multiple of ``10^q``, as text: plain in :data:`PLAIN` (or when
    ``sci`` is False), else ``m.mmme-k`` with every digit down to ``10^q``."""
    if d == 0:
        return "0" if q >= 0 else "0." + "0" * -q if sci is not True else "0"
    plain = PLAIN[0] <= abs(d) < PLAIN[1] if sci is None else not sci
    if plain:
        return format(_round(d, min(q, 0)), "f")
    e = d.adjusted()
    mant = _round(d.scaleb(-e, _EXACT), min(q - e, 0))
    return f"{format(mant, 'f')}e{e}"


def _order_one(r: Decimal, q: int) -> bool:
    """True when ``r`` (a multiple of ``10^q``) prints plain in a scientific form: |r| in
    :data:`ORDER_ONE` and no significant digit left of the units dropped (``q <= 0``)."""
    return ORDER_ONE[0] <= abs(r) < ORDER_ONE[1] and q <= 0


def _round(d: Decimal, q: int, rounding: str = ROUND_HALF_EVEN) -> Decimal:
    return d.quantize(Decimal(1).scaleb(q, _EXACT), rounding=rounding, context=_EXACT)


def _significant_place(d: Decimal, n: int, rounding: str = ROUND_HALF_EVEN) -> tuple[Decimal, int]:
    """``d`` rounded to ``n`` significant digits, and the place of its last digit (a carry,
    9.96 -> 10.0, moves the place up so that still ``n`` digits show)."""
    if d == 0:
        return d, 1 - n
    q = d.adjusted() - n + 1
    r = _round(d, q, rounding)
    if r.adjusted() > d.adjusted():
        q += 1
        r = _round(d, q, rounding)
    return r, q


def fixed(x: float, decimals: int) -> str:
    """``x`` with ``decimals`` decimals, correctly rounded (half to even on the exact value)."""
    return format(_round(_decimal(x), -decimals), "f")


def significant(x: float, n: int) -> str:
    """``x`` to ``n`` significant digits, trailing zeros kept: a plain decimal in
    [10^-3, 10^6), else scientific."""
    d = _decimal(x)
    if d == 0:
        return "0"
    r, q = _significant_place(d, n)
    return _text(r, q)


def scientific(x: float, n: int) -> str:
    """``x`` to ``n`` significant digits times a power of ten (``-8.99e-15``); an order-1
    value (:data:`ORDER_ONE`) as a plain decimal with the same digits (``0.880``); ``0``
    for zero."""
    d = _decimal(x)
    if d == 0:
        return "0"
    r, q = _significant_place(d, n)
    return _text(r, q, sci=not _order_one(r, q))


def bound(x: float, n: int, sci: bool | None = None) -> str:
    """``|x|`` rounded *up* to ``n`` significant digits (0.0273622 -> 0.02737): a bound stays a
    bound. Plain or scientific as :func:`significant`; ``sci=True`` as :func:`scientific`
    (an order-1 bound plain), ``sci=False`` always plain."""
    d = abs(_decimal(x))
    if d == 0:
        return "0"
    r, q = _significant_place(d, n, ROUND_CEILING)
    return _text(r, q, not _order_one(r, q) if sci else sci)


def place(error: float) -> int:
    """The place ``q`` of the last digit an error allows: the least integer with
    ``error <= 0.5 10^q`` (for ``error = 0``, ``-400``: every digit a double has)."""
    e = abs(_decimal(error))
    if e == 0:
        return -400
    q = e.adjusted() + 2  # e < 10^(q-1), so 0.5 10^q >= e; walk down while q - 1 holds too
    while Decimal(5).scaleb(q - 2, _EXACT) >= e:
        q -= 1
    return q


def with_error(x: float, error: float, most: int = 17) -> str:
    """``x`` with the digits its absolute ``error`` allows (at most ``most`` significant ones,
    at least one): each printed digit is right, ``|printed - x_true| <= 10^q`` for the last
    place ``10^q``. A value that would print as ``0`` at the error's place (the error swamps
    it) prints as a bound instead, ``<= 2e-15``: ``|x| + error`` rounded up to one
    significant digit, at least ``|x_true|`` (:func:`noise_bound`)."""
    d = _decimal(x)
    q = place(error)
    if d != 0:
        q = max(q, d.adjusted() - most + 1)
    r = _round(d, q)
    if r == 0:
        return noise_bound(x, error)  # |x| <= 0.5 10^q: the error swamps it (rounding_noise)
    # no digit below 10^q; tens and beyond as a power of ten (120 would claim the units)
    return _text(r, q, sci=True if q > 0 else None)


def estimate_of(x: float, reference: float) -> str:
    """``x``, an estimate of a quantity whose correctly rounded double is ``reference`` (the
    AGM period), with the digits its error leaves right (:func:`with_error`): the error is
    ``|x - reference|`` plus ``reference``'s own half ulp, which bounds ``|x - true|``."""
    return with_error(x, abs(x - reference) + math.ulp(reference) / 2)


def distance_of(x: float, reference: float, most: int = 4) -> str:
    """``|x - true|``, ``reference`` the correctly rounded double of the true value (the AGM
    period): at most ``most`` significant digits and those ``reference``'s half ulp leaves
    (an error near 1e-15 against a period of 2 s has none: ``<= 2e-15``)."""
    d = abs(x - reference)
    return with_error(d, math.ulp(reference) / 2 + math.ulp(d), most)


def noise_bound(x: float, error: float) -> str:
    """``<= b``: ``b`` the exact ``|x| + |error|`` rounded *up* to one significant digit, in
    the form of :func:`bound` with ``sci=True`` (``<= 2e-15``; ``<= 0.3`` order 1), so that
    ``|x_true| <= |x| + error <= b``: a value its error swamps, printed as the size it is under."""
    s = _EXACT.add(abs(_decimal(x)), abs(_decimal(error)))
    if s == 0:
        return "0"
    r, q = _significant_place(s, 1, ROUND_CEILING)
    return "<= " + _text(r, q, not _order_one(r, q))


def rounding_noise(x: float, error: float) -> bool:
    """True when ``|x|`` is at most its error: the number says nothing beyond its size, and a
    presenter marks it (``≈ rounding``) instead of printing digits."""
    return abs(_decimal(x)) <= abs(_decimal(error))


def shown(quantity: str, x: float | int, error: float | None = None) -> str:
    """``x`` printed in the form :data:`POLICY` gives ``quantity``; an ``error`` form needs
    the quantity's ``error`` (its most digits are the form's ``digits``)."""
    form = POLICY[quantity]
    if form.kind == "integer":
        return str(int(x))
    if not math.isfinite(x):
        return "—"
    if form.kind == "fixed":
        return fixed(x, form.digits)
    if form.kind == "significant":
        return significant(x, form.digits)
    if form.kind == "scientific":
        return scientific(x, form.digits)
    if form.kind == "bound":
        return bound(x, form.digits)
    if error is None:
        raise ValueError(f"{quantity}: its form prints the digits its error allows; give error")
    return with_error(x, error, form.digits)
