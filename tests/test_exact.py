"""Inputs as written: angles and numbers parsed exactly."""
import math
from fractions import Fraction

import mpmath
import pytest

from pendulab.core.errors import InputError
from pendulab.core.inputs import parse_angle, parse_number
from reference import EXAMPLE_LENGTH_TEXT


@pytest.mark.parametrize(
    "text, value",
    [
        ("0.785", 0.785),
        ("pi/4", math.pi / 4),
        ("4pi/5", 4 * math.pi / 5),
        ("4*pi/5", 4 * math.pi / 5),
        ("45deg", math.pi / 4),
        ("45°", math.pi / 4),
        ("180 deg", math.pi),
        ("pi", math.pi),
        ("0.5pi", math.pi / 2),
        ("1/3", 1 / 3),
    ],
)
def test_angle_forms(text, value):
    assert float(parse_angle("amplitude", text)) == pytest.approx(value, rel=1e-15)


def test_angles_are_correctly_rounded():
    # 4pi/5 is the double nearest to the true 4 pi/5 (mpmath at 50 digits).
    with mpmath.workdps(50):
        assert float(parse_angle("a", "4pi/5")) == float(4 * mpmath.pi / 5)
        assert float(parse_angle("a", "1deg")) == float(mpmath.pi / 180)


def test_numbers_are_exact():
    assert parse_number("l", EXAMPLE_LENGTH_TEXT).coef == Fraction(20800838231, 10**10)
    assert parse_number("g", "9.80665").mpf(30) == mpmath.mpf("9.80665")


@pytest.mark.parametrize("text", ["", "abc", "pi/0", "4pi/", "45rad/deg", "1/0", "--1"])
def test_malformed(text):
    with pytest.raises(InputError):
        parse_angle("amplitude", text)


@pytest.mark.parametrize("text", ["1e99999999", "1e-99999999", "1" * 500])
def test_huge_literals_are_refused_quickly(text):
    # Fraction("1e99999999") would build a 10^8-digit integer and never return.
    with pytest.raises(InputError):
        parse_number("length", text)
    with pytest.raises(InputError):
        parse_angle("amplitude", text + "deg")


def _nearest_double_of_pi_times(c: Fraction) -> float:
    """The double nearest to ``c pi``: mpmath at 700 bits, rounded once by Fraction -> float
    (correctly rounded, subnormals and overflow included)."""
    with mpmath.workprec(700):
        sign, man, exp, _ = (mpmath.mpf(c.numerator) / c.denominator * mpmath.pi)._mpf_
    if not man:
        return 0.0
    try:
        return (-1.0) ** sign * float(Fraction(int(man)) * Fraction(2) ** int(exp))
    except OverflowError:
        return -math.inf if sign else math.inf


def test_multiples_of_pi_are_the_nearest_double():
    """float(Exact) of c pi over the whole double range: normal, subnormal, overflow."""
    import random

    from pendulab.core.exact import Exact, _pi_bounds

    for bits in (8, 128, 1000):
        lo, hi = _pi_bounds(bits)
        with mpmath.workprec(bits + 64):
            assert lo <= mpmath.pi * 2**bits <= hi and hi - lo <= 2
    rng = random.Random(3)
    for _ in range(2000):
        c = Fraction(rng.randrange(-10**12, 10**12), rng.randrange(1, 10**12)) * Fraction(10) ** rng.randint(-330, 330)
        assert float(Exact(c, 1)) == _nearest_double_of_pi_times(c), c
