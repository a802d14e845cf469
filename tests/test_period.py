"""The exact period, (7)-(8): against mpmath's elliptic K, scipy's ellipkm1, and itself."""
import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.core.errors import InputError
from pendulab.numerics.period import (
    agm_iterations,
    agm_period,
    fixed_iterations_error,
    fixed_iterations_limit,
    period_digits,
    small_angle_period,
)
from reference import G, period_mp, reference_period

# Amplitudes on a uniform grid and ever closer to pi, down to 1e-12 away: K(m) is singular
# there, and the AGM must still be right.
GRID = np.concatenate([np.linspace(0.0, 3.1, 63), math.pi - np.logspace(-1, -12, 23)])


@pytest.mark.parametrize("alpha", GRID)
def test_agm_matches_mpmath_ellipk_to_1e15(alpha):
    ref = reference_period(2.5, alpha)
    got = agm_period(2.5, alpha)
    assert abs(got / ref - 1) <= 1e-15


def test_vectorised_equals_scalar_and_broadcasts():
    vec = agm_period(2.5, GRID)
    assert vec.shape == GRID.shape
    assert np.array_equal(vec, [agm_period(2.5, a) for a in GRID])
    lengths = np.array([[0.5], [3.5]])
    both = agm_period(lengths, GRID[:5])
    assert both.shape == (2, 5)
    assert both[1, 3] == agm_period(3.5, GRID[3])


def test_agm_matches_scipy_ellipkm1():
    # scipy's ellipkm1(p) = K(1 - p) takes p = cos^2(alpha/2) without cancellation.
    from scipy.special import ellipkm1

    ref = 4 * np.sqrt(2.5 / G) * ellipkm1(np.cos(GRID / 2) ** 2)
    assert np.allclose(agm_period(2.5, GRID), ref, rtol=5e-15, atol=0)


def test_scipy_ellipk_loses_digits_near_pi():
    # The reason the AGM does not route through ellipk(m): m = sin^2(alpha/2) rounds to 1.
    from scipy.special import ellipk

    alpha = math.pi - 1e-9
    naive = 4 * math.sqrt(1 / G) * ellipk(math.sin(alpha / 2) ** 2)
    ref = float(reference_period(1, alpha))
    assert abs(naive / ref - 1) > 1e-9
    assert abs(agm_period(1, alpha) / ref - 1) <= 1e-15


def test_small_angle_limit_and_formula():
    assert agm_period(1.0, 0.0) == small_angle_period(1.0) == pytest.approx(2 * math.pi * math.sqrt(1 / G), rel=1e-16)
    # T ~ T0 (1 + alpha^2/16) for small alpha (series of K, DLMF 19.5.1).
    a = 1e-3
    assert agm_period(1.0, a) / small_angle_period(1.0) == pytest.approx(1 + a * a / 16, rel=1e-12)


def test_seven_iterations_reproduce_spec_and_are_exact_for_moderate_amplitudes():
    # Seven steps of (7) in double precision give the same double as that loop run to
    # convergence; both carry the loop's rounding, so they are within 2 ulp of the
    # correctly rounded period (not always equal to it).
    from pendulab.numerics.period import agm_mean

    t0 = small_angle_period(1.0)
    for alpha in np.linspace(0, 3.14, 50):
        t_hat = agm_period(1.0, alpha, iterations=7)
        assert t_hat == t0 / agm_mean(math.cos(alpha / 2))
        assert abs(t_hat - agm_period(1.0, alpha)) <= 2 * math.ulp(t_hat)


@pytest.mark.parametrize("iterations", [0, 1, 3, 7])
def test_fixed_count_is_the_coursework_loop_interpreted_and_compiled(iterations):
    # One AGM loop in double precision: the interpreter runs it for one amplitude and for
    # arrays shorter than COMPILED_MIN, numba for longer ones. Both must be the coursework
    # program's loop (agm.py's t_hat), bit for bit, amplitudes up to pi - 1e-15.
    from pendulab.jobs.coursework import load
    from pendulab.numerics.period import COMPILED_MIN

    t_hat = load()["agm.py"].t_hat
    rng = np.random.default_rng(iterations)
    alpha = np.concatenate([rng.uniform(0, math.pi, COMPILED_MIN), math.pi - np.logspace(-1, -15, 50), [0.0]])
    plain = np.array([t_hat(2.5, a, G, iterations) for a in alpha.tolist()])
    for part in (alpha, alpha[-100:]):  # compiled, interpreted
        assert np.array_equal(agm_period(2.5, part, G, iterations=iterations), plain[-part.size:])
    assert agm_period(2.5, float(alpha[7]), G, iterations=iterations) == plain[7]


def test_converged_mean_same_bits_everywhere_and_within_two_ulps_of_mpmath():
    from pendulab.numerics.period import COMPILED_MIN, agm_mean

    rng = np.random.default_rng(5)
    b0 = np.concatenate([rng.uniform(0, 1, COMPILED_MIN), np.logspace(-300, 0, 100)])
    compiled, interpreted = agm_mean(b0), agm_mean(b0[-200:])
    assert np.array_equal(compiled[-200:], interpreted)
    assert all(agm_mean(float(b)) == v for b, v in zip(b0[::97].tolist(), compiled[::97], strict=True))
    with mpmath.workdps(40):
        for b, v in zip(b0[::50].tolist(), compiled[::50], strict=True):
            assert abs(v - float(mpmath.agm(1, b))) <= 2 * math.ulp(v)


def test_fixed_iterations_limit_brackets_the_truncation_error():
    limit = fixed_iterations_limit(7)
    assert math.pi - 1e-12 < limit < math.pi
    # Just below the limit the truncation error of 7 steps is under half an ulp;
    # just above it, over (measured independently at 80 digits).
    with mpmath.workdps(80):
        below = mpmath.pi - (mpmath.pi - mpmath.mpf(limit)) * 3
        above = mpmath.pi - (mpmath.pi - mpmath.mpf(limit)) / 3

        def truncation(alpha):
            b0 = mpmath.cos(alpha / 2)
            a, b = mpmath.mpf(1), b0
            for _ in range(7):
                a, b = (a + b) / 2, mpmath.sqrt(a * b)
            return (a + b) / 2 / mpmath.agm(1, b0) - 1

        assert truncation(below) < 2.0**-53 < truncation(above)
        assert fixed_iterations_error(above, 7) == pytest.approx(truncation(above), rel=1e-6)


def test_iterations_needed_grow_near_pi():
    counts = [agm_iterations(a) for a in (0.0, 1.0, 3.0, math.pi - 1e-12)]
    assert counts[0] == 0
    assert counts == sorted(counts)
    assert counts[-1] <= 10


def test_period_digits_every_digit_right():
    # Reference: l = 7/2, alpha = 4 pi/5 exactly, g = 980665/100000, via ellipk at 80 digits.
    with mpmath.workdps(80):
        m = mpmath.sin(2 * mpmath.pi / 5) ** 2
        ref = 4 * mpmath.sqrt(mpmath.mpf(7) / 2 / (mpmath.mpf(980665) / 100000)) * mpmath.ellipk(m)
        expected = mpmath.nstr(ref, 40, strip_zeros=False)
    assert period_digits("3.5", "4pi/5", digits=40) == expected


def test_period_digits_takes_inputs_as_written_not_as_doubles():
    exact = mpmath.mpf(period_digits("3.5", "4pi/5", digits=30))
    from_double = period_mp(3.5, 4 * math.pi / 5, dps=40)
    # The double 4pi/5 differs from 4 pi/5 by ~1e-16: the periods differ at that level.
    assert 1e-18 < abs(exact - from_double) < 1e-14


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"length": 0, "amplitude": 1}, "length"),
        ({"length": -1, "amplitude": 1}, "length"),
        ({"length": float("inf"), "amplitude": 1}, "length"),
        ({"length": 1, "amplitude": math.pi}, "amplitude"),
        ({"length": 1, "amplitude": -0.1}, "amplitude"),
        ({"length": 1, "amplitude": float("inf")}, "amplitude"),
        ({"length": 1, "amplitude": 1, "g": 0}, "g"),
        ({"length": 1, "amplitude": 1, "iterations": -1}, "iterations"),
        ({"length": 1, "amplitude": np.array([0.1, 4.0])}, "amplitude"),
    ],
)
def test_bad_input_names_the_argument(kwargs, name):
    with pytest.raises(InputError) as err:
        agm_period(**kwargs)
    assert err.value.name == name
    assert name in str(err.value)


@settings(max_examples=200, deadline=None)
@given(
    length=st.floats(1e-3, 1e3),
    a1=st.floats(0, math.pi, exclude_max=True),
    a2=st.floats(0, math.pi, exclude_max=True),
)
def test_invariants(length, a1, a2):
    # T grows with the amplitude, is at least the small-angle period, and scales as sqrt(l).
    lo, hi = sorted((a1, a2))
    assert agm_period(length, lo) <= agm_period(length, hi)
    assert agm_period(length, lo) >= small_angle_period(length) * (1 - 1e-15)
    assert agm_period(4 * length, hi) == pytest.approx(2 * agm_period(length, hi), rel=1e-15)


def test_signatures_name_their_types_and_exact_inputs_are_their_doubles():
    """help() shows what the public functions take and give (no ``Any``), and an ``Exact``
    (a number as written) is taken as its double, as the signatures say."""
    import inspect

    from pendulab.core.inputs import parse_angle, parse_number
    from pendulab.numerics.period import agm_mean

    for f in (agm_period, small_angle_period, agm_mean):
        sig = inspect.signature(f)
        shown = [str(p.annotation) for p in sig.parameters.values()] + [str(sig.return_annotation)]
        assert not any("Any" in s for s in shown), (f.__name__, shown)
        assert "Exact" in shown[0] and "ArrayLike" in shown[0] and "NDArray" in shown[-1], (f.__name__, shown)
    length, alpha = parse_number("length", "3.5"), parse_angle("amplitude", "4pi/5")
    assert agm_period(length, alpha) == agm_period(3.5, float(alpha))
    assert agm_period(length, alpha, iterations=7) == agm_period(3.5, float(alpha), iterations=7)
    assert small_angle_period(length) == small_angle_period(3.5)
    assert agm_mean(parse_number("b0", "0.5")) == agm_mean(0.5) == pytest.approx(float(mpmath.agm(1, 0.5)), rel=1e-15)
