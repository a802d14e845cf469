"""The digit policy (:mod:`pendulab.core.digits`): each form against an independent
computation in exact rationals, over every boundary (Hypothesis), and its table in docs."""
from __future__ import annotations

import math
import re
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from pendulab.core import digits

ROOT = Path(__file__).resolve().parents[1]
finite = st.floats(allow_nan=False, allow_infinity=False, min_value=-1e300, max_value=1e300)
positive = st.floats(min_value=1e-300, max_value=1e300)


def value(text: str) -> Fraction:
    """The exact value of a printed number (``-1.25e-5`` too)."""
    mant, exp = digits.split(text)
    return Fraction(mant) * Fraction(10) ** (exp or 0)


def last_place(text: str) -> int:
    """The place 10^q of the last digit printed."""
    mant, exp = digits.split(text)
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return (exp or 0) - decimals


@given(finite, st.integers(0, 20))
def test_fixed_is_correctly_rounded(x, d):
    text = digits.fixed(x, d)
    assert text == f"{x:.{d}f}"  # Python's format rounds the exact binary value correctly
    assert abs(value(text) - Fraction(x)) <= Fraction(1, 2) * Fraction(10) ** -d


@given(finite, st.integers(1, 17))
def test_significant_digits_and_rounding(x, n):
    text = digits.significant(x, n)
    if x == 0:
        assert text == "0"
        return
    mant, _ = digits.split(text)
    shown = mant.lstrip("-").replace(".", "").lstrip("0")
    assert len(shown) == n or ("." not in mant and len(shown) > n)  # trailing zeros kept; 10 is "10"
    assert value(text) == Fraction(Decimal(f"{x:.{n - 1}e}"))  # format rounds the exact value
    assert ("e" not in text) == (Fraction(1, 1000) <= abs(value(text)) < 10**6)


@given(finite, st.integers(1, 17))
def test_bound_is_the_least_above(x, n):
    text = digits.bound(x, n)
    b, a = value(text), abs(Fraction(x))
    if b == 0:
        assert x == 0
        return
    # the place of the n-th digit (20 for 11 to 1 digit: its zero is not a claim)
    unit = Fraction(10) ** (Decimal(b.numerator / b.denominator).adjusted() - n + 1)
    assert b >= a and b - a < unit  # rounded up, by less than one unit of its last place


@given(positive)
def test_place_is_the_least_allowed(error):
    q = digits.place(error)
    e = Fraction(error)
    assert e <= Fraction(1, 2) * Fraction(10) ** q
    assert e > Fraction(1, 2) * Fraction(10) ** (q - 1)


@pytest.mark.parametrize(("error", "q"), [(0.5, 0), (5.0, 1), (50.0, 2), (0.500001, 1), (0.4999999, 0),
                                          (5e-16, -14), (4.9e-16, -15), (2.5e-16, -15), (5.0000001e-15, -13)])
def test_place_at_the_boundaries(error, q):
    """0.5 10^q exactly (0.5, 5, 50 are doubles), a hair either side, and 5e-16 (a double just above)."""
    assert digits.place(error) == q


@given(finite, positive)
def test_with_error_prints_only_right_digits(x, error):
    """Every value within ``error`` of ``x`` (the truth may be any of them) is within one
    unit of the printed number's last place, and one more digit would not be."""
    text = digits.with_error(x, error)
    if text.startswith("<= "):  # the error swamps x: a bound of the true value's size
        q = digits.place(error)
        assert abs(Fraction(x)) <= Fraction(1, 2) * Fraction(10) ** q
        bound = value(text[3:])
        size = abs(Fraction(x)) + Fraction(error)  # every truth within error of x is at most this
        assert size <= bound < 2 * size  # rounded up to one significant digit: at most doubled
        assert len(text[3:].split("e")[0].replace(".", "").strip("0")) == 1, text
        return
    q = last_place(text)
    unit = Fraction(10) ** q
    worst = abs(value(text) - Fraction(x)) + Fraction(error)
    assert worst <= unit
    if q > math.floor(math.log10(abs(x))) - 16 if x else True:  # not cut by the 17-digit cap
        assert Fraction(error) > Fraction(1, 2) * Fraction(10) ** (q - 1)


@given(st.floats(min_value=1e-3, max_value=1e3), st.floats(min_value=-0.5, max_value=0.5),
       st.fractions(min_value=-1, max_value=1))
def test_an_estimate_of_a_rounded_reference_prints_only_right_digits(reference, off, where):
    """``estimate_of(x, T)``: T a correctly rounded double, so the truth is anywhere within
    T's half ulp of it; every such truth is within one unit of the printed last place."""
    x = reference * (1 + off * 10.0 ** -(abs(where.numerator) % 16))  # estimates from 0 to 15 digits right
    text = digits.estimate_of(x, reference)
    truth = Fraction(reference) + where * Fraction(math.ulp(reference)) / 2
    if text.startswith("<= "):
        assert abs(truth) <= value(text[3:])
    else:
        assert abs(value(text) - truth) <= Fraction(10) ** last_place(text)


@given(st.floats(min_value=1e-3, max_value=1e3), st.floats(min_value=-0.5, max_value=0.5),
       st.integers(0, 16), st.fractions(min_value=-1, max_value=1))
def test_a_distance_to_a_rounded_reference_prints_only_right_digits(reference, off, digits_right, where):
    """``distance_of(x, T)``: ``|x - true|`` for any truth within T's half ulp, within one unit
    of the printed last place (a bound ``<= b`` at least it)."""
    x = reference * (1 + off * 10.0 ** -digits_right)
    text = digits.distance_of(x, reference)
    truth = abs(Fraction(x) - (Fraction(reference) + where * Fraction(math.ulp(reference)) / 2))
    if text.startswith("<= "):
        assert truth <= value(text[3:])
    else:
        assert abs(value(text) - truth) <= Fraction(10) ** last_place(text)
        shown = digits.split(text)[0].replace(".", "").replace("-", "").lstrip("0")
        assert len(shown) <= 4 or shown.rstrip("0") == "1"  # 4 digits; a carry to 10^k adds its zero


def test_the_issues_numbers():
    """x_0 = 60 degrees from its radians, and the 3(d) coefficient of issue 32."""
    x0 = math.degrees(math.radians(60))
    assert x0 != 60 and digits.with_error(x0, 1.3e-14) == "60.0000000000000"
    assert digits.bound(0.0273622, 4) == "0.02737"
    assert digits.scientific(-8.99e-15, 3) == "-8.99e-15"
    assert digits.significant(0.88, 3) == "0.880" and digits.significant(11.2674, 6) == "11.2674"


def test_scientific_forms_print_order_one_values_plain():
    """|x| in [0.1, 1000) as a plain decimal with the same significant digits (issue 30:
    not ``8.80 × 10^-1``); beyond, a power of ten; a carry decides on the rounded value."""
    assert digits.scientific(0.8796, 3) == "0.880" and digits.scientific(11.26741, 6) == "11.2674"
    assert digits.scientific(0.3, 1) == "0.3" and digits.scientific(-4.236, 2) == "-4.2"
    assert digits.scientific(0.09996, 3) == "0.100" and digits.scientific(0.0996, 2) == "0.10"
    assert digits.scientific(0.09, 2) == "9.0e-2" and digits.scientific(2.963e-5, 3) == "2.96e-5"
    assert digits.scientific(999.96, 3) == "1.00e3" and digits.scientific(123.4, 2) == "1.2e2"
    assert digits.bound(1.13e-6, 2, sci=True) == "1.2e-6" and digits.bound(0.27361, 2, sci=True) == "0.28"
    assert digits.bound(0.0273622, 4) == "0.02737"  # the plain form keeps its range


def test_shown_follows_the_policy():
    assert digits.shown("p4.normal", 401.0) == "401.000000"
    assert digits.shown("p1.error_bound", 0.0273622) == "0.02737"
    with pytest.raises(ValueError, match="give error"):
        digits.shown("p5.estimate", 1.0)
    with pytest.raises(ValueError, match="kind"):
        digits.Form("rounded", 3)


def test_the_docs_table_is_the_policy():
    """docs/report.md lists every quantity of :data:`POLICY` with its form, and no other."""
    text = (ROOT / "docs" / "report.md").read_text(encoding="utf-8")
    rows = re.findall(r"^\| `([a-z0-9_.]+)` \| (\w+) \| (\d+) \|", text, flags=re.M)
    assert {name: digits.Form(kind, int(n)) for name, kind, n in rows} == digits.POLICY


def test_a_value_its_error_swamps_prints_as_a_bound():
    """Issue 32: f(x_4) = 2.2e-16 with an error 2 u S = 7.3e-16, the last step -9.0e-15 with two
    iterates' delta 5.1e-15, q_2 = 0.336 with a 28 % rounding error: not a bare 0 at the error's
    place but at most |x| + error, rounded up (the report's Typst: a true ≤)."""
    from pendulab.report.markup import typst

    assert digits.with_error(2.2e-16, 7.3e-16, 3) == "<= 1e-15"
    assert digits.with_error(-9.0e-15, 5.1e-15, 3) == "<= 2e-14"
    assert digits.with_error(0.336, 0.28 * 0.336) == "<= 0.5"
    assert digits.with_error(0.0, 0.0) == "0"  # exactly zero, and known so
    assert digits.with_error(1.2e-8, 5.1e-15, 3) == "1.20e-8"  # a value above its error: digits
    assert typst("<= 2e-14") == "≤ 2 × 10#super[−14]" and typst("<= 0.5") == "≤ 0.5"
