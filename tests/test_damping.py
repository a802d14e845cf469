"""The damped pendulum theta'' = -(g/l) sin(theta) - gamma theta' - beta theta'|theta'|.

References: scipy's DOP853 at rtol 1e-13 on the same equation (an integrator independent
of the library's kernels); the undamped runs of the library bit for bit where both
coefficients are 0; the energy lost against the work of the damping force, integrated by
the trapezoidal rule along a DOP853 solution.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from pendulab import simulate
from pendulab.core.errors import InputError
from reference import G

ALPHA, LENGTH, T_END = math.radians(30), 1.0, 2.0


def _reference(gamma, beta, t_end=T_END, alpha=ALPHA, length=LENGTH, t_eval=None):
    def f(_t, z):
        return [z[1], -G / length * math.sin(z[0]) - gamma * z[1] - beta * z[1] * abs(z[1])]

    return solve_ivp(f, (0.0, t_end), [alpha, 0.0], method="DOP853", rtol=1e-13, atol=1e-15,
                     t_eval=[t_end] if t_eval is None else t_eval)


@pytest.mark.parametrize("method", ["taylor2", "rk4", "verlet", "taylor:1", "taylor:5"])
def test_no_damping_is_the_undamped_run_bit_for_bit(method):
    plain = simulate(LENGTH, ALPHA, 0.01, T_END, method=method)
    zero = simulate(LENGTH, ALPHA, 0.01, T_END, method=method, damping=0.0, drag=0.0)
    assert np.array_equal(plain.theta, zero.theta) and np.array_equal(plain.omega, zero.omega)


@pytest.mark.parametrize(("method", "order"), [("taylor2", 2), ("rk4", 4), ("verlet", 2), ("taylor:1", 1), ("taylor:4", 4)])
def test_each_method_converges_at_its_order_with_a_linear_damping(method, order):
    # The largest error over the run at the coarse step's times (one end point can be near a zero of the error).
    h = 0.02 if order < 4 else 0.08
    t = h * np.arange(round(T_END / h) + 1)
    ref = _reference(0.4, 0.0, t_eval=t).y[0]
    errs = [np.max(np.abs(simulate(LENGTH, ALPHA, h / k, T_END, method=method, damping=0.4, stride=k).theta - ref))
            for k in (1, 2)]
    slope = math.log2(errs[0] / errs[1])
    assert slope == pytest.approx(order, abs=0.3), errs


@pytest.mark.parametrize("method", ["taylor2", "rk4", "verlet", "taylor:4"])
def test_each_method_converges_with_a_quadratic_drag(method):
    # theta'|theta'| has a kink at theta' = 0 (C^1 only): at least second order over a run.
    ref = _reference(0.1, 0.5)
    errs = [abs(simulate(LENGTH, ALPHA, h, T_END, method=method, damping=0.1, drag=0.5).theta[-1] - ref.y[0, -1])
            for h in (0.02, 0.01)]
    assert errs[1] < 1e-4 and math.log2(errs[0] / errs[1]) > 1.7, errs


def test_the_energy_lost_is_the_work_of_the_damping():
    # E0 - E(t) = int_0^t (gamma theta'^2 + beta |theta'|^3) dt (per unit m l^2): the heat.
    gamma, beta = 0.3, 0.4
    t = np.linspace(0.0, T_END, 20001)
    ref = _reference(gamma, beta, t_eval=t)
    w = ref.y[1]
    power = gamma * w ** 2 + beta * np.abs(w) ** 3
    heat = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))])
    tr = simulate(LENGTH, ALPHA, 1e-4, T_END, method="rk4", damping=gamma, drag=beta)
    energy = 0.5 * tr.omega ** 2 - G / LENGTH * np.cos(tr.theta)
    lost = (-G / LENGTH * math.cos(ALPHA)) - energy
    assert lost[-1] == pytest.approx(heat[-1], rel=1e-6) and lost[-1] > 0.5 * (G / LENGTH) * (1 - math.cos(ALPHA))


@settings(max_examples=40, deadline=None)
@given(value=st.one_of(st.floats(max_value=-1e-300), st.just(math.nan), st.just(math.inf)))
def test_a_negative_or_not_finite_damping_is_refused(value):
    for name in ("damping", "drag"):
        with pytest.raises(InputError, match=f"^{name} = .* must be a finite number >= 0"):
            simulate(LENGTH, ALPHA, 0.01, T_END, **{name: value})
