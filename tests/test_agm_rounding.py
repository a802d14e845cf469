"""agm_period returns the correctly rounded period: the double nearest to the true period.

References: mpmath's elliptic K at 60 digits (``T = 4 sqrt(l/g) K(sin^2(alpha/2))``, a
formula independent of the AGM), rounded once to the nearest double.
"""
import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.engine.agm import (
    COS_HI,
    COS_LO,
    ERROR_BOUND,
    N_TABLE,
    SIN_HI,
    SIN_LO,
    agm_periods_dd,
    half_angle_cos,
)
from pendulab.numerics.period import agm_period, nearest_period
from reference import G, reference_period


def nearest(length, alpha, g=G):
    """The true period of the exact doubles, rounded to the nearest double."""
    with mpmath.workdps(60):
        ref = reference_period(length, alpha, g, dps=60)
        return mpmath.libmp.to_float(ref._mpf_, rnd="n")


RNG = np.random.default_rng(12)
RANDOM_ALPHA = RNG.uniform(0, math.pi, 2000)
RANDOM_LENGTH = RNG.uniform(0.05, 20, 2000)
# Within 1e-15 of pi (the last 8 doubles below pi included), and below 1e-150.
below_pi = [math.pi]
for _ in range(8):
    below_pi.append(math.nextafter(below_pi[-1], 0))
HARD = np.concatenate([math.pi - np.logspace(-1, -15, 57), below_pi[1:], [1e-300, 5e-324, 1e-160, 0.0],
                       np.nextafter(math.pi / 2, [0, 4])])


@pytest.mark.slow
def test_2000_random_pendulums_are_correctly_rounded():
    got = agm_period(RANDOM_LENGTH, RANDOM_ALPHA)
    ref = [nearest(length, a) for length, a in zip(RANDOM_LENGTH, RANDOM_ALPHA)]
    assert np.array_equal(got, ref)


def test_hard_amplitudes_near_pi_and_zero_are_correctly_rounded():
    got = agm_period(1.0, HARD)
    ref = [nearest(1.0, a) for a in HARD]
    assert np.array_equal(got, ref)
    assert agm_period(1.0, 3.14159265358972) == nearest(1.0, 3.14159265358972)


def test_scalar_path_gives_the_same_doubles():
    for length, alpha in zip(RANDOM_LENGTH[:50], RANDOM_ALPHA[:50]):
        assert agm_period(length, alpha) == agm_period(np.array([length]), np.array([alpha]))[0]


@pytest.mark.slow
def test_double_double_value_is_within_the_error_bound():
    # The kernel's unrounded th + tl against the reference at 60 digits.
    alpha = np.concatenate([RANDOM_ALPHA[:300], HARD])
    out, lo, hard = np.empty(alpha.size), np.empty(alpha.size), np.empty(alpha.size, np.int64)
    assert agm_periods_dd(alpha, np.array([2.5]), G, out, lo, hard)[1] == -1
    with mpmath.workdps(60):
        worst = max(abs((mpmath.mpf(h) + mpmath.mpf(low)) / reference_period(2.5, a, dps=60) - 1)
                    for h, low, a in zip(out, lo, alpha))
    assert worst < ERROR_BOUND / 2**10


@pytest.mark.slow
def test_half_angle_cos_is_accurate_to_double_double():
    from numba import njit

    f = njit(lambda a: half_angle_cos(a))
    # Amplitudes on both sides of every table interval's ends, y = (pi - alpha)/2 = (i + 1/2)/N.
    ends = math.pi - (2 * np.arange(int(math.pi / 2 * N_TABLE) + 1) + 1) / N_TABLE
    edges = (ends[:, None] + np.array([-1e-3, -1e-12, 0.0, 1e-12, 1e-3])).ravel()
    alpha = np.concatenate([RANDOM_ALPHA[:400], HARD[:-4], edges[(edges >= 0) & (edges < math.pi)]])
    with mpmath.workdps(50):
        for a in alpha:
            h, low = f(a)
            ref = mpmath.cos(mpmath.mpf(a) / 2)
            assert abs((mpmath.mpf(h) + mpmath.mpf(low)) / ref - 1) < 2.0**-89


def test_sin_cos_table_is_exact_to_double_double():
    with mpmath.workdps(50):
        for i, row in enumerate(zip(SIN_HI, SIN_LO, COS_HI, COS_LO)):
            y = mpmath.mpf(i) / N_TABLE
            for (hi, lo), ref in zip((row[:2], row[2:]), (mpmath.sin(y), mpmath.cos(y))):
                assert hi == mpmath.libmp.to_float(ref._mpf_, rnd="n")  # the nearest double
                assert abs(mpmath.mpf(hi) + mpmath.mpf(lo) - ref) <= 2.0**-106 * max(abs(ref), 2.0**-8)
    assert (len(SIN_HI) - 1) / N_TABLE > math.pi / 2 + 0.5 / N_TABLE  # every y in [0, pi/2] has a row


def test_failed_rounding_tests_are_recomputed():
    # A few amplitudes in 10^6 fail the cheap test; find some and check they come out right.
    alpha = np.random.default_rng(0).uniform(0, math.pi, 1_000_000)
    out, index = np.empty(alpha.size), np.empty(alpha.size, np.int64)
    count, bad = agm_periods_dd(alpha, np.array([1.0]), G, out, out[:0], index)
    assert bad == -1
    hard = alpha[index[:count]]
    assert 0 < len(hard) < 20
    assert np.array_equal(agm_period(1.0, hard), [nearest(1.0, a) for a in hard])


@pytest.mark.slow
def test_extreme_lengths_and_g_give_representable_periods():
    # l/g under- or overflows, the period does not: sqrt(l)/sqrt(g).
    assert agm_period(1e-300, 1.0, g=1e300) == nearest(1e-300, 1.0, 1e300)
    assert agm_period(1e150, 1.0, g=1e-300) == nearest(1e150, 1.0, 1e-300)
    assert 0 < agm_period(1e-300, 1.0, g=1e300) < 1e-298
    both = agm_period(np.array([1e-300, 1e150]), 1.0, g=1e300)
    assert both[0] == nearest(1e-300, 1.0, 1e300)
    assert both[1] == nearest(1e150, 1.0, 1e300)
    assert agm_period(np.array([1e150]), 1.0, g=1e-300)[0] == nearest(1e150, 1.0, 1e-300)


def test_nearest_period_agrees_with_the_elliptic_k_reference():
    for a in (0.0, 1e-8, 1.0, 3.0, math.pi - 1e-12):
        assert nearest_period(3.5, a, G) == nearest(3.5, a)


@settings(max_examples=60, deadline=None)
@given(st.floats(0, math.pi, exclude_max=True), st.floats(1e-3, 1e3))
def test_any_pendulum_is_correctly_rounded(alpha, length):
    assert agm_period(np.array([length]), np.array([alpha]))[0] == nearest(length, alpha)


def test_errors_of_the_double_loop_are_gone():
    # The plain double-precision AGM is off by an ulp or more somewhere in these 2000.
    from pendulab.numerics.period import agm_mean, small_angle_period

    plain = [small_angle_period(length) / agm_mean(math.cos(a / 2)) for length, a in zip(RANDOM_LENGTH, RANDOM_ALPHA)]
    assert not np.array_equal(plain, agm_period(RANDOM_LENGTH, RANDOM_ALPHA))


@pytest.mark.parametrize("n", [1, 31, 32, 33, 95])
def test_block_edges(n):
    alpha = RANDOM_ALPHA[:n]
    assert np.array_equal(agm_period(1.5, alpha), [nearest(1.5, a) for a in alpha])


@pytest.mark.parametrize("bad", [math.pi, -0.0 - 1e-300, math.nan, math.inf, -1e300, 7.0])
def test_the_kernel_refuses_amplitudes_outside_0_pi(bad):
    # Checked in the kernel's own pass (an amplitude out of range would index past the table).
    alpha = np.concatenate([RANDOM_ALPHA[:40], [bad], RANDOM_ALPHA[40:50], [bad]])
    out, index = np.empty(alpha.size), np.empty(alpha.size, np.int64)
    assert agm_periods_dd(alpha, np.array([1.0]), G, out, out[:0], index)[1] == 40
    if math.isnan(bad):  # agm_period: a missing amplitude, NaN in that element only
        got = agm_period(1.0, alpha)
        assert np.isnan(got).tolist() == np.isnan(alpha).tolist()
        return
    with pytest.raises(ValueError, match=r"amplitude\[40\]"):
        agm_period(1.0, alpha)


# The scalar route: agm_period of plain floats runs the one-pendulum kernel (agm_period_dd).
SCALAR_ALPHA = np.concatenate([RANDOM_ALPHA[:300], HARD])


@pytest.mark.slow
def test_scalar_kernel_value_is_within_the_error_bound():
    # The unrounded th + tl of the one-pendulum kernel against the reference at 60 digits,
    # on random amplitudes, those within 1e-15 of pi, below 1e-150, and extreme l/g.
    from numba import njit

    from pendulab.engine.agm import period_dd

    f = njit(lambda a, length, g: period_dd(a, length, g))
    cases = [(a, 2.5, G) for a in SCALAR_ALPHA] + [(a, 1e-150, 1e150) for a in HARD[::7]] \
        + [(a, 1e150, 1e-150) for a in HARD[::7]]
    with mpmath.workdps(60):
        worst = max(abs((mpmath.mpf(h) + mpmath.mpf(low)) / reference_period(length, a, g, dps=60) - 1)
                    for a, length, g in cases for h, low in [f(a, length, g)])
    assert worst < ERROR_BOUND / 2**10


def test_scalar_periods_are_correctly_rounded_and_equal_the_array_path():
    floats = [float(a) for a in SCALAR_ALPHA]
    got = [agm_period(2.5, a) for a in floats]
    assert got == [nearest(2.5, a) for a in floats]
    assert np.array_equal(got, agm_period(2.5, SCALAR_ALPHA))
    # Every length of the random set, as Python floats and as numpy scalars (the checked route).
    lengths = [float(x) for x in RANDOM_LENGTH]
    got = [agm_period(length, float(a)) for length, a in zip(lengths, RANDOM_ALPHA)]
    assert np.array_equal(got, agm_period(RANDOM_LENGTH, RANDOM_ALPHA))
    assert got[:100] == [agm_period(length, a) for length, a in zip(RANDOM_LENGTH[:100], RANDOM_ALPHA[:100])]


def test_scalar_failed_rounding_tests_are_recomputed(monkeypatch):
    # Where the kernel's rounding test fails (it returns -1) mpmath gives the period.
    from pendulab.numerics import period

    agm_period(1.0, 0.5)  # the kernel loaded
    monkeypatch.setattr(period, "_scalar_period_kernel", lambda a, length, g: -1.0)
    for a in (0.0, 1e-8, 1.0, 3.0, below_pi[1]):
        assert agm_period(3.5, a) == nearest(3.5, a)
    # The amplitudes where the array kernel's test failed, by the scalar route.
    monkeypatch.undo()
    alpha = np.random.default_rng(0).uniform(0, math.pi, 1_000_000)
    out, index = np.empty(alpha.size), np.empty(alpha.size, np.int64)
    count, _ = agm_periods_dd(alpha, np.array([1.0]), G, out, out[:0], index)
    assert [agm_period(1.0, float(a)) for a in alpha[index[:count]]] == [nearest(1.0, a) for a in alpha[index[:count]]]


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(st.floats(0, math.pi, exclude_max=True),
       st.floats(1e-300, 1e300) | st.sampled_from([1e-150, 1e150, math.nextafter(1e-150, 0), math.nextafter(1e150, 2e150)]),
       st.sampled_from([G, 1e-150, 1e150, 1.0, math.nextafter(1e150, 2e150)]))
def test_any_scalar_pendulum_is_correctly_rounded(alpha, length, g):
    # Over the whole range of each input, both sides of the unchecked route's edges.
    from pendulab.core.errors import InputError

    try:
        got = agm_period(length, alpha, g)
    except InputError as exc:  # only a period beyond MAX_PERIOD is refused
        assert "period" in str(exc)
        with mpmath.workdps(30):
            assert reference_period(length, 0.0, g, dps=30) > 1e299
        return
    assert got == nearest(length, alpha, g)
    assert got == agm_period(np.array([length]), np.array([alpha]), g)[0]


@pytest.mark.parametrize("bad", [math.pi, -1e-300, math.inf, 7.0, -0.5])
def test_scalar_bad_amplitudes_are_refused(bad):
    with pytest.raises(ValueError, match="amplitude"):
        agm_period(1.0, bad)


def test_scalar_nan_gives_nan_by_either_route():
    # numpy's convention (numerics/arrays.py): a NaN argument gives NaN, not an error.
    for args in ((1.0, math.nan), (math.nan, 1.0), (np.float64(1.0), np.float64(math.nan))):
        assert math.isnan(agm_period(*args)) and math.isnan(agm_period(*args, iterations=7))


@pytest.mark.parametrize(("length", "g", "name"), [(0.0, G, "length"), (-1.0, G, "length"), (math.inf, G, "length"),
                                                   (5e-324, G, "length"), (1.0, 0.0, "g"), (1.0, math.nan, "g"),
                                                   (1e300, 1e-300, "length")])
def test_scalar_bad_lengths_and_g_are_refused(length, g, name):
    with pytest.raises(ValueError, match=name):
        agm_period(length, 1.0, g)


@settings(max_examples=200, deadline=None)
@given(st.floats(0, math.pi, exclude_max=True), st.floats(1e-300, 1e300), st.integers(0, 12))
def test_scalar_t_hat_is_the_checked_routes_double(alpha, length, n):
    # T^ of plain floats (unchecked route) against numpy scalars (the checked route) and
    # the loop (7)-(8) written out: the same double.
    from pendulab.core.errors import InputError

    try:
        slow = agm_period(np.float64(length), np.float64(alpha), iterations=n)
    except InputError:
        return
    assert agm_period(length, alpha, iterations=n) == slow
    if 1e-150 <= length <= 1e150:
        a, b = 1.0, math.cos(0.5 * alpha)
        for _ in range(n):
            a, b = 0.5 * (a + b), math.sqrt(a * b)
        assert slow == 2 * math.pi * math.sqrt(length / G) / (0.5 * (a + b))
