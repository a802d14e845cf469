"""Problem 1: g from l and T, propagated errors, guaranteed significant digits."""
import itertools
import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from uncertainties import ufloat

from pendulab.core.errors import InputError
from pendulab.numerics.uncertainty import gravity_estimate, round_significant, significant_digits

L, DL, T, DT = 1.152, 0.003, 2.1536, 2e-4  # problem 1(b): 115.2 cm, 0.3 cm, 2.1536 s, 2e-4 s


def test_g_against_mpmath():
    r = gravity_estimate(L, DL, T, DT)
    with mpmath.workdps(40):  # 4 pi^2 l / T^2 from the decimal inputs as written
        ref = 4 * mpmath.pi**2 * mpmath.mpf("1.152") / mpmath.mpf("2.1536") ** 2
    assert r.g == pytest.approx(float(ref), rel=4e-16)


def test_first_order_bound_against_uncertainties_derivatives():
    # uncertainties differentiates g = 4 pi^2 l / T^2 itself; the first-order bound is
    # sum |dg/dx| dx (it would report the quadrature sum as std_dev, a different quantity).
    length, t = ufloat(L, DL), ufloat(T, DT)
    g = 4 * math.pi**2 * length / t**2
    bound = abs(g.derivatives[length]) * DL + abs(g.derivatives[t]) * DT
    r = gravity_estimate(L, DL, T, DT)
    assert r.abs_error == pytest.approx(bound, rel=1e-12)
    assert r.dg_dl == pytest.approx(g.derivatives[length], rel=1e-12)
    assert r.dg_dT == pytest.approx(g.derivatives[t], rel=1e-12)
    assert r.rel_error == pytest.approx(bound / g.nominal_value, rel=1e-12)
    assert r.g == pytest.approx(g.nominal_value, rel=1e-15)


def test_worst_case_against_monte_carlo_and_corners():
    r = gravity_estimate(L, DL, T, DT)
    rng = np.random.default_rng(1)
    ls = rng.uniform(L - DL, L + DL, 200_000)
    ts = rng.uniform(T - DT, T + DT, 200_000)
    dev = np.abs(4 * np.pi**2 * ls / ts**2 - r.g)
    assert dev.max() <= r.worst_error * (1 + 1e-12)
    assert dev.max() > 0.95 * r.worst_error  # the sample comes close to the corners
    # Exact corners in rational arithmetic (pi^2 factored out): the worst case is a corner.
    gq = Fraction(L) / Fraction(T) ** 2
    corners = [abs(Fraction(L + a * DL) / Fraction(T + b * DT) ** 2 - gq) for a, b in itertools.product((-1, 1), repeat=2)]
    assert r.worst_error == pytest.approx(4 * math.pi**2 * float(max(corners)), rel=1e-9)
    # First order and exact bounds differ by a second-order term only.
    assert abs(r.worst_error - r.abs_error) < 10 * r.g * r.rel_error**2
    assert r.error_bound == max(r.worst_error, r.abs_error)


def test_problem1_answer_two_significant_digits():
    r = gravity_estimate(L, DL, T, DT)
    assert r.significant_digits == 2
    assert r.g_text == "9.8"
    # The definition, checked directly: leading digit at 10^0, error <= 0.5e-1 but not <= 0.5e-2.
    assert r.error_bound <= 0.05 and not r.error_bound <= 0.005
    assert r.g_min < 9.8 < r.g_max


@pytest.mark.parametrize("value, error, digits", [
    (98.0, 0.5, 2),          # exactly half a unit of the 2nd digit (0.5 is a double)
    (9.8, 0.05, 1),          # the double 0.05 is 0.05000000000000000277 > 1/20: the rule on its exact value
    (99.99999999999999, 0.4, 2),  # just below 10^2: log10 rounds to 2.0, the leading digit is at 10^1
    (9.8, 0.0500001, 1),
    (123.4, 0.5, 3),
    (123.4, 0.51, 2),
    (0.01234, 4e-6, 4),
    (-2.5, 0.04, 2),
    (7.0, 6.0, 0),           # error above half a unit of the leading digit
    (1.0, 0.0, 15),
])
def test_significant_digits_definition(value, error, digits):
    assert significant_digits(value, error) == digits


def test_round_significant_is_half_away_from_zero():
    assert round_significant(0.125, 2) == "0.13"  # 0.125 is exact in binary; round() gives 0.12
    assert round_significant(-0.125, 2) == "-0.13"
    assert round_significant(9.805779670743561, 3) == "9.81"


@pytest.mark.parametrize("args, name", [
    ((L, -DL, T, DT), "length_error"),
    ((L, DL, T, -DT), "period_error"),
    ((L, DL, 0.0, DT), "period"),
    ((-L, DL, T, DT), "length"),
    ((L, DL, T, T), "period_error"),
    ((L, L, T, DT), "length_error"),
    ((L, DL, math.nan, DT), "period"),
])
def test_bad_inputs_name_the_argument(args, name):
    with pytest.raises(InputError) as exc:
        gravity_estimate(*args)
    assert exc.value.name == name
