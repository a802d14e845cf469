"""The exact motion of a launched pendulum against scipy's DOP853 at rtol 1e-12 (an
independent integration of theta'' = -(g/l) sin theta), for libration and circulation; next to
the separatrix and at rest near pi against mpmath at 50 digits beyond the cancellation, to
the stated bound (launched_motion_error_bound)."""
from __future__ import annotations

import math
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from pendulab.numerics.launched import launch, launched_motion
from pendulab.numerics.motion import exact_motion
from reference import G, ellipk_period

EPS = 2.0**-52


def reference(length, alpha, omega0, t, g=G):
    c = g / length
    sol = solve_ivp(lambda _, z: [z[1], -c * math.sin(z[0])], (0, t[-1]), [alpha, omega0], method="DOP853",
                    rtol=1e-12, atol=1e-12, t_eval=t)
    return sol.y


@pytest.mark.parametrize("length, alpha, omega0", [
    (1.0, 0.5, 2.0),        # libration, launched towards larger theta
    (1.0, 0.5, -2.0),       # towards the bottom first
    (3.5, 2.5, 1.0),        # a large swing
    (1.0, 0.0, 6.0),        # from the bottom, just below the top (k = 0.958)
    (1.0, 0.3, 7.0),        # over the top: circulation
    (2.0, 2.0, -5.0),       # round the other way
    (1.0, 3.0, 0.5),        # near the top, going over
])
def test_launched_motion_is_the_pendulums(length, alpha, omega0):
    t = np.linspace(0, 20, 801)
    theta, omega = launched_motion(length, alpha, omega0, t)
    ref = reference(length, alpha, omega0, t)
    assert np.max(np.abs(theta - ref[0])) < 1e-8 and np.max(np.abs(omega - ref[1])) < 1e-8
    info = launch(length, alpha, omega0)
    w = math.sqrt(G / length)
    assert info.k == pytest.approx(math.hypot(math.sin(alpha / 2), omega0 / (2 * w)), rel=1e-15)
    if info.circulates:
        # Once round in the stated time: theta(t + T) = theta(t) +- 2 pi.
        th2, _ = launched_motion(length, alpha, omega0, np.array([info.period]))
        assert abs(th2[0] - alpha) == pytest.approx(2 * math.pi, rel=1e-10)
        assert info.turning_angle is None
    else:
        # The turning angle and the period are those of a release at rest there.
        assert info.period == pytest.approx(ellipk_period(length, info.turning_angle), rel=1e-12)
        assert np.max(np.abs(theta)) <= info.turning_angle * (1 + 1e-12)


def test_no_velocity_is_the_release_at_rest():
    t = np.linspace(0, 10, 101)
    theta, omega = launched_motion(1.0, 2.0, 0.0, t)
    ex = exact_motion(1.0, 2.0, t)
    assert np.allclose(theta, ex.theta, rtol=0, atol=1e-12) and np.allclose(omega, ex.omega, rtol=0, atol=1e-12)


# ---------------------------------------------------------------------------- near the separatrix
# Independent reference: mpmath's ellipfun with m' = cos^2(alpha/2) - omega0^2/(4 w^2) from the exact
# doubles (benchmarks/adversarial.py, launched_reference).
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import adversarial  # noqa: E402

from pendulab.numerics.launched import launched_motion_error_bound  # noqa: E402
from pendulab.numerics.motion import exact_motion_error_bound  # noqa: E402

# Issue 32: l = 0.537, alpha = 2.731 and omega0 giving k = 1 - 1e-12.
ISSUE_LAUNCH = (0.537, 2.731, 1.7423259334447145)


def within_bound(length, alpha, omega0, t, g=G):
    theta, omega = launched_motion(length, alpha, omega0, t, g)
    bt, bo = launched_motion_error_bound(length, alpha, omega0, t, g)
    for i, ti in enumerate(t):
        ref_theta, ref_omega = adversarial.launched_reference(length, alpha, omega0, ti, g)
        assert abs(theta[i] - ref_theta) <= bt[i], (ti, theta[i], ref_theta)
        assert abs(omega[i] - ref_omega) <= bo[i], (ti, omega[i], ref_omega)
    return theta, omega


def test_issue_launch_half_a_period_on_is_at_the_other_side():
    length, alpha, omega0 = ISSUE_LAUNCH
    info = launch(length, alpha, omega0)
    assert not info.circulates and 1 - info.k == pytest.approx(1e-12, rel=1e-3)
    t = np.array([0.0, info.period / 2, info.period, 1e4 * info.period + 0.3 * info.period])
    theta, omega = within_bound(length, alpha, omega0, t)
    assert theta[1] == pytest.approx(-alpha, abs=1e-12)  # at half the period, the mirror image
    assert np.all(np.abs(omega) <= 2 * info.k * math.sqrt(G / length) * (1 + 1e-15))


@pytest.mark.parametrize("delta", [1e-9, -1e-9, 2e-12, -2e-12, 1e-15, -1e-15, 4e-16, -4e-16])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_within_the_bound_next_to_the_separatrix_for_ten_thousand_periods(delta, sign):
    """k^2 = 1 - delta, both sides; zero crossings, turning points and a random phase up to 10^4 periods."""
    length, alpha = 0.537, 2.731
    omega0 = adversarial.separatrix_launch(length, alpha, G, delta, sign)
    info = launch(length, alpha, omega0)
    assert info.circulates == (delta < 0) and math.isfinite(info.period)
    t = np.array([0.25, 0.5, 0.75, 1.0, 137.61, 1e4 + 0.25, -1e4 - 0.5]) * info.period
    theta, _ = within_bound(length, alpha, omega0, t)
    if info.circulates:  # once round a turn's time: theta(T) = alpha + 2 pi s
        assert theta[3] == pytest.approx(alpha + 2 * math.pi * sign, abs=1e-12)


def test_on_the_separatrix_the_limit_forms():
    """l = g, omega0 = 2 w from the bottom: m' = 0 exactly, theta = 2 gd(w t) (DLMF 4.23.39)."""
    info = launch(G, 0.0, 2.0)
    assert info.period == math.inf and not info.circulates and info.turning_angle == math.pi
    t = np.array([0.0, 0.5, 3.0, 40.0, 800.0, -2.0])
    theta, omega = launched_motion(G, 0.0, 2.0, t)
    ref = [2 * mpmath.atan(mpmath.sinh(mpmath.mpf(ti))) for ti in t]  # w = 1
    assert np.all(np.abs(theta - np.array(ref, dtype=float)) <= 4 * EPS * np.maximum(1, np.abs(theta)))
    ref_omega = np.array([2 / mpmath.cosh(mpmath.mpf(ti)) for ti in t], dtype=float)
    assert np.all(np.abs(omega - ref_omega) <= 4 * EPS * 2)


@pytest.mark.parametrize("alpha", [math.pi - 1e-7, math.pi - 1e-8, math.pi - 1e-12, math.nextafter(math.pi, 0),
                                   math.pi])
def test_at_rest_near_pi_it_is_exact_motion(alpha):
    """Released at rest within 1e-7 of pi down to the last doubles below it: the period of
    (8) and exact_motion's theta, theta' to the stated bound."""
    length = 1.0
    info = launch(length, alpha, 0.0)
    with mpmath.workdps(90):  # 4 K(m)/w with 1 - m = cos^2(alpha/2) carried to 90 digits (DLMF 19.2.8)
        kp = mpmath.cos(mpmath.mpf(alpha) / 2)
        period = float(4 * mpmath.ellipk(1 - kp * kp) / mpmath.sqrt(mpmath.mpf(G) / length))
    assert info.period == pytest.approx(period, rel=4 * EPS)
    t = np.array([0.0, 0.25, 0.5, 0.75, 3.3, 1e4 + 0.25]) * info.period
    theta, omega = within_bound(length, alpha, 0.0, t)
    if alpha == math.pi:  # fl(pi) < pi: exact_motion takes it as outside [0, pi)
        return
    ex = exact_motion(length, alpha, t)
    bt, bo = launched_motion_error_bound(length, alpha, 0.0, t)
    et, _ = exact_motion_error_bound(length, alpha, t)
    assert np.all(np.abs(theta - ex.theta) <= bt) and np.all(np.abs(omega - ex.omega) <= bo)
    assert np.all(bt <= 4 * et)  # exact_motion's bound, times max(1, |theta|) <= pi


def test_the_adversarial_search_stays_within_the_bound():
    """benchmarks/adversarial.py's launched_search with a small budget."""
    found = adversarial.launched_search(40)
    assert found["worst"] <= 1.0, found
