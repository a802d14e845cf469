"""The exact motion of a launched pendulum against scipy's DOP853 at rtol 1e-12 (an
independent integration of theta'' = -(g/l) sin theta), for libration and circulation."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from pendulab.numerics.launched import launch, launched_motion
from pendulab.numerics.motion import exact_motion
from reference import G, ellipk_period


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
