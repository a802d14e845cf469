"""Newton's divided differences and the inverse cubic, against scipy and a known function."""
import math
from fractions import Fraction

import numpy as np
import pytest
from scipy.interpolate import BarycentricInterpolator

from pendulab.core.errors import InputError
from pendulab.numerics.interpolation import divided_differences, inverse_cubic, newton_eval
from reference import EXAMPLE_LENGTH


def test_newton_form_agrees_with_scipy_barycentric():
    rng = np.random.default_rng(1)
    x = np.sort(rng.uniform(-1, 1, 6))
    y = rng.normal(size=6)
    coef = divided_differences(x, y)
    xs = np.linspace(-1, 1, 17)
    assert np.allclose(newton_eval(coef, x, xs), BarycentricInterpolator(x, y)(xs), atol=1e-10)
    assert np.allclose(newton_eval(coef, x, x), y, atol=1e-12)


def test_leading_coefficient_is_the_polynomial_leading_coefficient():
    x = np.array([0.0, 1.0, 3.0, 4.0])
    y = 2 * x**3 - x + 5
    assert divided_differences(x, y)[-1] == pytest.approx(2.0)


def test_inverse_cubic_estimates_its_own_error():
    # t(z) = arcsin(z): the zero is t = 0; nodes straddle it like z2 in problem 3(d).
    z = np.array([0.35, 0.12, -0.08, -0.31])
    t = np.arcsin(z) + 5.0
    fifth = (0.5, np.arcsin(0.5) + 5.0)
    res = inverse_cubic(z, t, fifth)
    true_error = 5.0 - res.value
    assert abs(true_error) < 1e-3
    # The estimate has the right order of magnitude (it is an estimate, not a bound).
    assert 0.1 < abs(res.error_estimate / true_error) < 10


def test_repeated_nodes_are_rejected():
    with pytest.raises(InputError, match="distinct"):
        divided_differences([0.0, 0.0, 1.0], [1.0, 2.0, 3.0])
    with pytest.raises(InputError, match="distinct"):  # the fifth node too
        inverse_cubic([1.0, 0.5, -0.5, -1.0], [0.0, 1.0, 2.0, 3.0], (0.5, -1.0))


# ------------------------------------------------------------------ scaling and the rounding level


def exact_error_estimate(z2, t):
    """``t[z2_0..z2_4] prod_(j<4)(0 - z2_j)`` in exact rationals (the doubles' exact values)."""
    x = [Fraction(float(v)) for v in z2]
    y = [Fraction(v) if isinstance(v, Fraction) else Fraction(float(v)) for v in t]
    dd = 0
    for k in range(5):
        den = Fraction(1)
        for i in range(5):
            if i != k:
                den *= x[k] - x[i]
        dd += y[k] / den
    return dd * math.prod(-xi for xi in x[:4])


def test_scaled_nodes_give_the_same_bits():
    z = np.array([0.35, 0.12, -0.08, -0.31])
    t = np.arcsin(z) + 5.0
    ref = inverse_cubic(z, t, (0.5, math.asin(0.5) + 5.0))
    assert np.array_equal(ref.coefficients, divided_differences(z, t))  # reported unscaled
    for e in (-600, -1000, 300):
        r = inverse_cubic(np.ldexp(z, e), t, (math.ldexp(0.5, e), math.asin(0.5) + 5.0))
        assert r.value == ref.value and r.error_estimate == ref.error_estimate
        assert r.rounding_level == ref.rounding_level
    tiny = inverse_cubic(np.ldexp(z, -1000), t, (math.ldexp(0.5, -1000), math.asin(0.5) + 5.0))
    assert np.isinf(tiny.fourth_difference)  # the true t[z0..z4] ~ 2^4000 exceeds the doubles


def test_error_estimate_below_rounding_level_is_flagged():
    from pendulab.numerics.crossing import estimate_period

    # The README's h = 1e-4 row: the estimate 4.4e-17 comes from rounding t_k = k h.
    est = estimate_period(EXAMPLE_LENGTH, 4 * math.pi / 5, 1e-4)
    ip = est.interpolation
    h = Fraction(est.step)
    exact_t = [(est.j - 2 + k) * h for k in range(5)]  # t_k = k h with no rounding
    # inverse_cubic's nodes: window points 1..4 (the cubic), then point 0 (the fifth).
    exact = exact_error_estimate([*ip.z2, ip.fifth[0]], [*exact_t[1:], exact_t[0]])
    assert abs(exact) < 1e-19  # the interpolation error proper (-6.7e-21)
    assert abs(ip.error_estimate) <= ip.rounding_level and not ip.error_estimate_resolved
    assert abs(ip.error_estimate - float(exact)) <= ip.rounding_level
    # At h = 1e-2 the estimate is interpolation error, far above the rounding level.
    est = estimate_period(EXAMPLE_LENGTH, 4 * math.pi / 5, 1e-2)
    ip = est.interpolation
    exact_t = [(est.j - 2 + k) * Fraction(est.step) for k in range(5)]
    exact = exact_error_estimate([*ip.z2, ip.fifth[0]], [*exact_t[1:], exact_t[0]])
    assert ip.error_estimate_resolved and ip.error_estimate == pytest.approx(float(exact), rel=1e-6)


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=100, deadline=None)
@given(e=st.integers(-1000, 1000), seed=st.integers(0, 2**32 - 1))
def test_scaling_by_any_power_of_two_keeps_the_bits(e, seed):
    rng = np.random.default_rng(seed)
    z = np.sort(rng.uniform(-1, 1, 5))[::-1]
    if len(set(z)) < 5:
        return
    t = 5.0 + np.arcsin(z)
    ref = inverse_cubic(z[1:], t[1:], (z[0], t[0]))
    got = inverse_cubic(np.ldexp(z[1:], e), t[1:], (math.ldexp(z[0], e), t[0]))
    assert (got.value, got.error_estimate, got.rounding_level) == (ref.value, ref.error_estimate, ref.rounding_level)
