"""The exact motion (motion.py) against mpmath's Jacobi elliptic functions."""
import math

import mpmath
import numpy as np
import pytest

from pendulab.core.errors import InputError
from pendulab.numerics.motion import energy, energy_drift, exact_motion, global_error, jacobi, quarter_period
from pendulab.numerics.period import agm_period
from pendulab.numerics.simulation import simulate
from reference import EXAMPLE_LENGTH, G


def mp_motion(length, alpha, t, dps=40):
    """theta, theta' from mpmath: sin(theta/2) = k sn(K - w t | k^2), cos(theta/2) = dn, theta' = -2 k w cn.

    Inputs are the exact binary values of the doubles; everything else at ``dps`` digits.
    """
    with mpmath.workdps(dps):
        a = mpmath.mpf(alpha)
        k = mpmath.sin(a / 2)
        m = k * k
        w = mpmath.sqrt(mpmath.mpf(G) / mpmath.mpf(length))
        u = mpmath.ellipk(m) - w * mpmath.mpf(t)
        sn, cn, dn = (mpmath.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn"))
        return float(2 * mpmath.atan2(k * sn, dn)), float(-2 * k * w * cn)


# Amplitudes from small to within 1e-12 of pi: both the scipy path (k' >= 0.1) and the AGM path.
AMPLITUDES = [1e-3, 0.5, math.pi / 4, 2.0, 2.9, 3.0, 3.14, math.pi - 1e-4, math.pi - 1e-8, math.pi - 1e-12]


@pytest.mark.parametrize("alpha", AMPLITUDES)
def test_exact_motion_matches_mpmath(alpha):
    length = EXAMPLE_LENGTH
    period = agm_period(length, alpha)
    t = np.linspace(0, 2.5 * period, 17)
    ex = exact_motion(length, alpha, t)
    ref = np.array([mp_motion(length, alpha, ti) for ti in t])
    # A few ulps of theta: the phase t/T is exact to 2^-104 (exact_motion_error_bound).
    assert np.max(np.abs(ex.theta - ref[:, 0])) <= 16 * 2.0**-52
    w = math.sqrt(G / length)
    assert np.max(np.abs(ex.omega - ref[:, 1])) <= 16 * 2.0**-52 * w


def test_scipy_alone_loses_digits_near_pi_and_the_fallback_does_not():
    """Why the AGM from k' exists: scipy's ellipj(u, m = k^2) near alpha = pi."""
    from scipy.special import ellipj

    alpha = math.pi - 1e-8
    k = math.sin(alpha / 2)
    u = np.linspace(0.1, 0.99, 9) * quarter_period(alpha)
    sn, _, dn, _ = ellipj(u, k * k)
    naive = 2 * np.arctan2(k * sn, dn)
    with mpmath.workdps(40):
        m = mpmath.sin(mpmath.mpf(alpha) / 2) ** 2
        ref = np.array([float(2 * mpmath.atan2(mpmath.sqrt(m) * mpmath.ellipfun("sn", ui, m=m),
                                               mpmath.ellipfun("dn", ui, m=m))) for ui in u])
    ours = jacobi(u, alpha)
    mine = 2 * np.arctan2(k * ours[0], ours[2])
    assert np.max(np.abs(naive - ref)) > 1e-10  # scipy alone: digits lost
    assert np.max(np.abs(mine - ref)) < 1e-14


def test_quarter_period_matches_mpmath_near_pi():
    for alpha in (0.3, 3.0, math.pi - 1e-10):
        with mpmath.workdps(40):
            ref = mpmath.ellipk(mpmath.sin(mpmath.mpf(alpha) / 2) ** 2)
        assert quarter_period(alpha) == pytest.approx(float(ref), rel=4e-16)


@pytest.mark.parametrize("kp", [0.15, 0.5, 0.95])
def test_jacobi_agm_agrees_with_scipy_away_from_pi(kp):
    # Away from pi scipy's ellipj is accurate to a few ulps: the AGM from k' must agree.
    from scipy.special import ellipj

    from pendulab.numerics.motion import jacobi_agm

    k = math.sqrt(1 - kp * kp)
    u = np.linspace(-7, 7, 29)
    s1, s2 = jacobi_agm(u, k, kp), ellipj(u, k * k)[:3]
    for x, y in zip(s1, s2):
        assert np.all(np.abs(x - y) < 1e-15 * (1 + np.abs(u)))  # rounding grows with |u|


def test_motion_is_periodic_and_starts_at_rest():
    alpha, length = 2.5, 1.0
    T = agm_period(length, alpha)  # the AGM period (8), an independent computation
    ex = exact_motion(length, alpha, [0.0, T / 4, T / 2, T])
    assert ex.theta[0] == pytest.approx(alpha, abs=1e-15)
    assert ex.omega[0] == pytest.approx(0, abs=1e-15)
    assert ex.theta[1] == pytest.approx(0, abs=1e-14)  # bottom at a quarter period
    assert ex.theta[2] == pytest.approx(-alpha, abs=1e-14)
    assert ex.theta[3] == pytest.approx(alpha, abs=1e-14)


def test_exact_motion_conserves_energy():
    alpha, length = math.pi - 1e-5, 0.5
    t = np.linspace(0, 30, 301)
    ex = exact_motion(length, alpha, t)
    e = energy(ex.theta, ex.omega, length)
    assert np.max(np.abs(e + G / length * math.cos(alpha))) < 1e-12 * G / length


def test_global_error_of_figure3():
    # Figure 3 of the coursework: z1 at t = 2.1 is 0.796774928412 (12 digits, as the coursework prints it).
    tr = simulate(1, math.pi / 4, 0.1, 2.1)
    ge = global_error(tr)
    theta_ref, omega_ref = mp_motion(1.0, math.pi / 4, 2.1)
    assert ge.theta_error[-1] == pytest.approx(0.796774928412 - theta_ref, abs=1e-12)
    assert ge.omega_error[-1] == pytest.approx(-0.297068336875 - omega_ref, abs=1e-11)
    assert ge.max_theta_error >= abs(ge.theta_error[-1])
    assert abs(ge.theta_error[0]) <= 2.3e-16 and ge.energy_drift[0] == pytest.approx(0, abs=1e-15)


def test_bad_inputs():
    with pytest.raises(InputError, match="amplitude"):
        exact_motion(1, math.pi, [0.0])
    with pytest.raises(InputError, match=r"t\[1\] = inf"):  # NaN is a missing time (NaN out), inf is refused
        exact_motion(1, 1.0, [0.0, math.inf])
    with pytest.raises(InputError, match="length"):
        exact_motion(0, 1.0, 1.0)


# ------------------------------------------------------------------ the error bound, densely
def mp_motion_many(length, alpha, ts, dps=60):
    """:func:`mp_motion` for many times; 60 digits: 1 - m = k'^2 is 2.5e-25 at pi - 1e-12."""
    out = []
    with mpmath.workdps(dps):
        a = mpmath.mpf(alpha)
        k = mpmath.sin(a / 2)
        m = k * k
        w = mpmath.sqrt(mpmath.mpf(G) / mpmath.mpf(length))
        big_k = mpmath.ellipk(m)
        for t in ts:
            u = big_k - w * mpmath.mpf(t)
            sn, cn, dn = (mpmath.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn"))
            out.append((float(2 * mpmath.atan2(k * sn, dn)), float(-2 * k * w * cn)))
    return np.array(out)


@pytest.mark.slow
@pytest.mark.parametrize("alpha", [2.0, math.pi - 1e-9, math.pi - 1e-12])
def test_exact_motion_within_its_bound_densely(alpha):
    # 1500 points over 2.5 periods (the 17 points above missed 7.9e-14 at pi - 1e-12).
    from pendulab.numerics.motion import exact_motion_error_bound

    length = EXAMPLE_LENGTH
    t = np.linspace(0, 2.5 * agm_period(length, alpha), 1500)
    ex = exact_motion(length, alpha, t)
    ref = mp_motion_many(length, alpha, t)
    bound_theta, bound_omega = exact_motion_error_bound(length, alpha, t)
    assert np.all(np.abs(ex.theta - ref[:, 0]) <= bound_theta)
    assert np.all(np.abs(ex.omega - ref[:, 1]) <= bound_omega)
    # The bound is not loose: the worst point uses at least a sixteenth of it (an ulp or two).
    assert np.max(np.abs(ex.theta - ref[:, 0]) / bound_theta) >= 1 / 16


@pytest.mark.parametrize("alpha", [0.5, math.pi - 1e-12])
def test_exact_motion_within_its_bound_after_1000_periods(alpha):
    from pendulab.numerics.motion import exact_motion_error_bound

    length = EXAMPLE_LENGTH
    period = agm_period(length, alpha)
    t = np.linspace(1000 * period, 1001 * period, 120)
    ex = exact_motion(length, alpha, t)
    ref = mp_motion_many(length, alpha, t)
    bound_theta, bound_omega = exact_motion_error_bound(length, alpha, t)
    err = np.abs(ex.theta - ref[:, 0])
    assert np.all(err <= bound_theta)
    assert np.all(np.abs(ex.omega - ref[:, 1]) <= bound_omega)
    # The error does not grow with t: a few ulps of theta, as in the first periods.
    assert err.max() <= 16 * 2.0**-52


def test_energy_drift_is_the_energy_difference_in_m_g_l():
    # (E - E0)/(m g l) with E/(m g l) = theta'^2 l/(2g) + 1 - cos(theta), in mpmath at 40 digits.
    rng = np.random.default_rng(5)
    theta, omega = rng.uniform(-3, 3, 50), rng.uniform(-5, 5, 50)
    alpha, w0, length = 2.5, 0.75, 3.5
    got = energy_drift(theta, omega, alpha, w0, length, G)
    with mpmath.workdps(40):
        def e(th, om):
            return mpmath.mpf(om) ** 2 * length / (2 * mpmath.mpf(G)) + 1 - mpmath.cos(th)

        ref = np.array([float(e(a, b) - e(alpha, w0)) for a, b in zip(theta, omega)])
    assert np.allclose(got, ref, rtol=0, atol=8 * np.finfo(float).eps)
    assert energy_drift(alpha, w0, alpha, w0, length, G) == 0.0
