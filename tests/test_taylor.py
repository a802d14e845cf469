"""The Taylor algorithm (3), (6): Figure 3, the step count, and its order."""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.core import cases
from pendulab.core.errors import InputError
from pendulab.numerics.simulation import kept_steps, simulate, step_count, stride_for
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


@settings(max_examples=300, deadline=None)
@given(n=st.integers(0, 3000), stride=st.integers(1, 400), data=st.data())
def test_kept_steps_are_every_stride_th_step_and_the_last(n, stride, data):
    # The rule written out (every step that is a multiple of stride, and the last), over
    # any range lo..hi, and consecutive pieces (i0, i1] add up to the whole run, as the
    # explorer's CSV reads them block by block.
    lo = data.draw(st.integers(0, n))
    hi = data.draw(st.integers(lo, n))
    plain = [i for i in range(lo, hi + 1) if i % stride == 0 or i == n]
    assert kept_steps(n, stride, lo, hi).tolist() == plain
    cuts = sorted(set(data.draw(st.lists(st.integers(0, n), max_size=5))) | {0, n})
    pieces = [kept_steps(n, stride, i0 + 1, i1) for i0, i1 in zip(cuts, cuts[1:])]
    assert [0, *np.concatenate([np.zeros(0, np.int64), *pieces]).tolist()] == kept_steps(n, stride).tolist()


@settings(max_examples=300, deadline=None)
@given(points=st.integers(2, 10**6), k=st.integers(0, 3000), d=st.integers(-2, 2))
def test_thinned_to_points_keeps_both_ends_and_at_most_points(points, k, d):
    # The worst cases sit next to the multiples of points - 1 (the search's n): one step
    # more and the stride must grow by one.
    n = max(0, k * (points - 1) + d)
    stride = stride_for(n, points)
    idx = kept_steps(n, stride)
    assert idx[0] == 0 and idx[-1] == n
    assert np.all(np.diff(idx) > 0)  # sorted, no repeats
    assert len(idx) <= points
    assert len(idx) == n + 1 or stride > 1  # all kept where all fit
    if stride > 1:  # the smallest stride that fits: one less keeps too many
        assert len(kept_steps(n, stride - 1)) > points
