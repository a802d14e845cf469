"""Certified digits: Arb balls from the exact inputs, checked against mpmath's elliptic K.

The references use ``4 sqrt(l/g) K(k)`` (DLMF 19.2.8) with ``mpmath.ellipk`` at a
working precision well above the digits compared, started from the exact inputs
(``k' = cos(alpha/2)`` from the exact distance to pi where the amplitude is a multiple of
pi): independent of Arb and of the AGM.
"""
import math
import random
from fractions import Fraction

import mpmath
import pytest
from flint import arb, ctx
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import assert_one_line_error
from pendulab.core.errors import InputError
from pendulab.numerics.period import period_ball, period_digits
from reference import G_TEXT, G, period_mp, reference_period_kp


def ref_period(length: str, alpha_coef: Fraction, pi_multiple: bool, g: str = G_TEXT, dps: int = 120):
    """:func:`reference.reference_period_kp` with ``k' = cos(alpha/2)``; for a multiple of pi,
    ``cos(c pi/2)`` from the exact ``1 - c`` (no cancellation)."""
    with mpmath.workdps(dps):
        c = mpmath.mpf(alpha_coef.numerator) / alpha_coef.denominator
        kp = mpmath.sin(mpmath.pi * (1 - c) / 2) if pi_multiple else mpmath.cos(c / 2)
        return reference_period_kp(length, kp, g)


@pytest.mark.parametrize(
    "amplitude, coef, pi_multiple",
    [
        ("4pi/5", Fraction(4, 5), True),
        ("0.9999999999999999999999999pi", Fraction("0.9999999999999999999999999"), True),
        ("0.999999999999999999999999999999999999999999pi", Fraction("0.999999999999999999999999999999999999999999"), True),
        # the double nearest pi, 1.2e-16 below it: within 1e-15 of pi
        ("3.141592653589793", Fraction("3.141592653589793"), False),
        ("3.1415926535897932384626433832795028841971", Fraction("3.1415926535897932384626433832795028841971"), False),
        ("1e-160", Fraction("1e-160"), False),
        ("1e-300", Fraction("1e-300"), False),
        ("0", Fraction(0), False),
    ],
)
@pytest.mark.parametrize("digits", [1, 5, 15, 40])
def test_digits_are_the_correctly_rounded_period(amplitude, coef, pi_multiple, digits):
    ref = ref_period("1", coef, pi_multiple, dps=digits + 150)
    with mpmath.workdps(digits + 150):
        expected = mpmath.nstr(ref, digits, strip_zeros=False)
    assert period_digits("1", amplitude, digits=digits) == expected


def test_range_check_runs_on_the_exact_amplitude():
    # Issue: refused at 5 digits because the amplitude was rounded to 20 digits first.
    assert period_digits("1", "0.9999999999999999999999999pi", digits=5) == "74.722"
    assert period_digits("1", "0.9999999999999999999999999pi", digits=15) == "74.7223655536862"
    # pi = 3.14159265358979323846264338327950288419716939937510582...: one digit past pi is refused,
    # the same digits rounded down are accepted, whatever the precision.
    with pytest.raises(InputError, match="amplitude"):
        period_digits("1", "3.14159265358979323846264338327950288419716939937511", digits=3)
    below = "3.1415926535897932384626433832795028841971693993751"
    with mpmath.workdps(200):
        expected = mpmath.nstr(ref_period("1", Fraction(below), False, dps=200), 3, strip_zeros=False)
    assert period_digits("1", below, digits=3) == expected
    for bad in ("pi", "1pi", "180deg", "-1e-300", "4"):
        with pytest.raises(InputError, match="amplitude"):
            period_digits("1", bad, digits=5)
    with pytest.raises(InputError, match="length"):
        period_digits("0", "1", digits=5)
    with pytest.raises(InputError, match="g"):
        period_digits("1", "1", g="-1e-300", digits=5)


def test_period_mp_takes_the_exact_amplitude_too():
    ref = ref_period("1", Fraction("0.9999999999999999999999999"), True, dps=80)
    got = period_mp("1", "0.9999999999999999999999999pi", dps=20)
    assert abs(got - ref) < 1e-17 * ref


def test_ball_contains_the_reference_and_shrinks_with_precision():
    rng = random.Random(12)
    for _ in range(25):
        coef = Fraction(rng.randrange(1, 10**12), 10**12)  # alpha = coef pi
        length = str(Fraction(rng.randrange(1, 10**6), 1000))
        ref = ref_period(length, coef, True, dps=80)
        for prec in (64, 200):
            ball = period_ball(length, f"{coef.numerator}pi/{coef.denominator}", prec=prec)
            old = ctx.prec
            ctx.prec = 300
            try:
                assert ball.contains(arb(mpmath.nstr(ref, 75)))  # ref known to 1e-75
            finally:
                ctx.prec = old
            assert float(ball.rad()) < 2.0 ** (-prec + 12) * float(ball.mid())


def test_random_inputs_match_mpmath():
    rng = random.Random(5)
    for _ in range(20):
        coef = Fraction(rng.randrange(0, 10**9), 10**9 + 7)
        amp = f"{coef.numerator}/{coef.denominator}"  # radians, a plain rational
        length = f"{rng.randrange(1, 10**5)}e-3"
        digits = rng.choice([3, 17, 30])
        ref = ref_period(length, coef, False, dps=digits + 60)
        with mpmath.workdps(digits + 60):
            assert period_digits(length, amp, digits=digits) == mpmath.nstr(ref, digits, strip_zeros=False)


def test_many_digits_agree_with_mpmath():
    got = period_digits("3.5", "4pi/5", digits=3000)
    ref = ref_period("3.5", Fraction(4, 5), True, dps=3100)
    with mpmath.workdps(3100):
        assert got == mpmath.nstr(ref, 3000, strip_zeros=False)


def test_more_digits_than_python_prints_an_int(cli):
    # str() refuses integers of more than 4300 digits (sys.get_int_max_str_digits()): the
    # CLI's largest --digits crashed with a traceback.
    got = period_digits("3.5", "4pi/5", digits=5000)
    ref = ref_period("3.5", Fraction(4, 5), True, dps=5100)
    with mpmath.workdps(5100):
        assert got == mpmath.nstr(ref, 5000, strip_zeros=False)
    res = cli("period", "-l", "3.5", "-a", "4pi/5", "--digits", "10000")
    assert res.code == 0, res.err
    line = res.out.splitlines()[0]  # period_as_written: the digits of 4 pi/5 as typed
    assert line.startswith("period_as_written, AGM")
    assert len(line.split("=")[1].split()[0].replace(".", "")) == 10000


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(n=st.integers(0, 10**12000))
def test_int_text_prints_any_length(n):
    import sys

    from pendulab.numerics.period import _int_text

    limit = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)  # the reference: str() without the limit
    try:
        expected = str(n)
    finally:
        sys.set_int_max_str_digits(limit)
    assert _int_text(n) == expected


def test_cli_period_digits_near_pi(cli):
    res = cli("period", "-l", "1", "-a", "0.99999999999999pi", "--digits", "30")
    assert res.code == 0, res.err
    ref = ref_period("1", Fraction("0.99999999999999"), True, dps=80)
    with mpmath.workdps(80):
        assert f"T  = {mpmath.nstr(ref, 30, strip_zeros=False)} s" in res.out
    assert_one_line_error(cli("period", "-l", "1", "-a", "1pi", "--digits", "5"), "amplitude")




@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(
    num=st.integers(0, 10**15 - 1),
    length=st.fractions(min_value=Fraction(1, 1000), max_value=1000, max_denominator=10**6),
    g=st.fractions(min_value=Fraction(1, 10), max_value=100, max_denominator=10**4),
)
def test_ball_always_contains_the_period(num, length, g):
    # Amplitudes c pi with c = num/10^15 in [0, 1): up to within 1e-15 pi of pi.
    coef = Fraction(num, 10**15)
    lt, gt = f"{length.numerator}/{length.denominator}", f"{g.numerator}/{g.denominator}"
    ball = period_ball(lt, f"{coef.numerator}pi/{coef.denominator}", gt, prec=96)
    with mpmath.workdps(60):
        kp = mpmath.sin(mpmath.pi * (1 - mpmath.mpf(coef.numerator) / coef.denominator) / 2)
        ref = 4 * mpmath.sqrt((mpmath.mpf(length.numerator) / length.denominator)
                              / (mpmath.mpf(g.numerator) / g.denominator)) * mpmath.ellipk(1 - kp * kp)
        text = mpmath.nstr(ref, 50)
    old = ctx.prec
    ctx.prec = 200
    try:
        assert ball.contains(arb(text))  # ref is within 1e-50 of the period; the ball is 1e-28 wide
    finally:
        ctx.prec = old


def test_seven_iterations_within_their_bound_up_to_the_truncation_limit():
    # FIXED_ITERATIONS_ULPS (derived in period.py): T^ of (8) is within 20 ulp of the
    # correctly rounded period up to pi - 3.24e-14, where the truncation reaches half an
    # ulp. The adversarial search is tests/test_bounds_adversarial.py; here random amplitudes.
    import numpy as np

    from pendulab.numerics.period import FIXED_ITERATIONS_ULPS, agm_period, fixed_iterations_limit

    limit = fixed_iterations_limit()
    assert 3.2e-14 < 3.141592653589793 - limit < 3.3e-14
    rng = np.random.default_rng(11)
    alphas = np.concatenate([rng.uniform(0, 3.1, 150),
                             3.141592653589793 - np.exp(rng.uniform(np.log(3.3e-14), np.log(1e-6), 150))])
    t_hat = agm_period(1.0, alphas, iterations=7)
    # 1 - m = cos^2(alpha/2) is 3e-28 at the limit: 70 digits keep 40 of it.
    with mpmath.workdps(70):
        ref = [float(reference_period_kp(1, mpmath.cos(mpmath.mpf(a) / 2), G)) for a in alphas]
    ulps = [abs(x - r) / math.ulp(r) for x, r in zip(t_hat, ref)]
    assert max(ulps) <= FIXED_ITERATIONS_ULPS


@pytest.mark.slow
@settings(max_examples=300, deadline=None)
@given(
    digits=st.integers(1, 60),
    lead=st.integers(0, 10**60),
    exponent=st.integers(-80, 80),
)
def test_decimal_text_is_mpmath_nstr_layout(digits, lead, exponent):
    """The proved decimal is printed as mpmath.nstr(x, digits, strip_zeros=False) prints it."""
    from pendulab.numerics.period import _decimal_text

    n = 10 ** (digits - 1) + lead % (9 * 10 ** (digits - 1))
    with mpmath.workdps(digits + 10):
        expected = mpmath.nstr(mpmath.mpf(n) * mpmath.mpf(10) ** exponent, digits, strip_zeros=False)
    assert _decimal_text(n, exponent, digits) == expected


@pytest.mark.parametrize("length", ["1e-30", "1e-6", "1e6", "1e40"])
def test_digits_of_tiny_and_huge_periods(length):
    ref = ref_period(length, Fraction(1, 3), False, dps=80)
    with mpmath.workdps(80):
        assert period_digits(length, "1/3", digits=20) == mpmath.nstr(ref, 20, strip_zeros=False)
