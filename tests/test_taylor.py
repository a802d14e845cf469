"""The Taylor algorithm (3), (6): Figure 3, the step count, and its order."""
import math

import numpy as np
import pytest

from pendulab import cases
from pendulab.errors import InputError
from pendulab.taylor import simulate, step_count
from reference import FIGURE3, G


def test_figure3_to_12_significant_digits():
    tr = simulate(1.0, math.pi / 4, 0.1, 2.1)
    assert tr.n_steps == 21
    for j, (t, z1, z2) in FIGURE3.items():
        assert f"{tr.t[j]:.12g}" == f"{t:.12g}"
        assert f"{tr.theta[j]:.12g}" == f"{z1:.12g}"
        assert f"{tr.omega[j]:.12g}" == f"{z2:.12g}"


def test_lists_of_problem3():
    tr = simulate(1.0, math.pi / 4, 0.1, 2.1)
    assert tr.time_series().shape == (22, 2)
    assert np.array_equal(tr.time_series()[:, 1], tr.phase_points()[:, 0])
    assert np.array_equal(tr.phase_points()[:, 1], tr.omega)


def _dop853(length, alpha, t_end):
    """theta, theta' at t_end by scipy's DOP853 at tight tolerances (an independent integrator)."""
    from scipy.integrate import solve_ivp

    c = -cases.G / length
    sol = solve_ivp(lambda t, y: [y[1], c * math.sin(y[0])], (0, t_end), [alpha, 0.0],
                    method="DOP853", rtol=1e-13, atol=1e-14)
    return sol.y[0, -1], sol.y[1, -1]


def test_one_step_has_third_order_local_error():
    """One step of (3) is the Taylor polynomial of degree 2: its error is O(h^3), halving h divides it by 8."""
    length, alpha = 2.08, 4 * math.pi / 5
    errors = []
    for h in (0.04, 0.02, 0.01, 0.005):
        tr = simulate(length, alpha, h, 2 * h)
        z1, z2 = _dop853(length, alpha, h)
        assert tr.t[1] == h
        errors.append(math.hypot(tr.theta[1] - z1, tr.omega[1] - z2))
    ratios = [e0 / e1 for e0, e1 in zip(errors, errors[1:])]
    assert all(7.5 < r < 8.5 for r in ratios), ratios


def test_start_time_only_shifts_the_times():
    """The equation is autonomous: from t0 = 1 the points are those from 0, at times t0 + j h."""
    shifted = simulate(2.08, 4 * math.pi / 5, 0.01, 10.0, t0=1.0)
    plain = simulate(2.08, 4 * math.pi / 5, 0.01, 9.0)
    assert shifted.n_steps == plain.n_steps == 900
    assert np.array_equal(shifted.theta, plain.theta) and np.array_equal(shifted.omega, plain.omega)
    assert shifted.t[0] == 1.0 and shifted.t[-1] == pytest.approx(10.0)


@pytest.mark.parametrize("t0, t_max, h, n", [(0, 2.1, 0.1, 21), (0, 1, 0.3, 3), (0, 1, 0.4, 2), (1, 2, 1e-3, 1000)])
def test_step_count_is_round_of_equation_6(t0, t_max, h, n):
    assert step_count(t0, t_max, h) == n


def test_global_error_is_second_order_against_scipy():
    # Reference trajectory: scipy's DOP853 at tight tolerance (an independent integrator).
    from scipy.integrate import solve_ivp

    length, alpha, g = 3.5, math.pi / 4, G
    sol = solve_ivp(lambda t, y: [y[1], -g / length * math.sin(y[0])], (0, 4), [alpha, 0.0],
                    method="DOP853", rtol=1e-13, atol=1e-13, dense_output=True)
    steps = [0.02, 0.01, 0.005, 0.0025]
    errors = []
    for h in steps:
        tr = simulate(length, alpha, h, 4.0)
        errors.append(np.max(np.abs(tr.theta - sol.sol(tr.t)[0])))
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert abs(slope - 2) < 0.1


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"step": 0}, "step"),
        ({"step": -0.1}, "step"),
        ({"step": float("nan")}, "step"),
        ({"step": 3.0}, "step"),
        ({"t_max": 0.0}, "t_max"),
        ({"t_max": -1.0}, "t_max"),
        ({"length": 0}, "length"),
        ({"amplitude": 4.0}, "amplitude"),
        ({"method": "euler"}, "method"),
    ],
)
def test_bad_input(kwargs, name):
    args = {"length": 1.0, "amplitude": 0.5, "step": 0.1, "t_max": 2.0} | kwargs
    with pytest.raises(InputError) as err:
        simulate(**args)
    assert err.value.name == name


@pytest.mark.parametrize("stride", [1, 3, 7, 100])
def test_thinned_storage_keeps_the_same_points(stride):
    full = simulate(2.08, 2.5, 1e-3, 5.0)
    thin = simulate(2.08, 2.5, 1e-3, 5.0, stride=stride)
    idx = list(range(0, 5001, stride))
    if idx[-1] != 5000:
        idx.append(5000)
    assert np.array_equal(thin.theta, full.theta[idx])
    assert np.array_equal(thin.omega, full.omega[idx])
    assert np.array_equal(thin.t, full.t[idx])
    assert thin.n_steps == full.n_steps == 5000


def test_bad_stride():
    with pytest.raises(InputError) as err:
        simulate(1.0, 0.5, 0.1, 2.0, stride=0)
    assert err.value.name == "stride"
