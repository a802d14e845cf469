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
