"""The Taylor algorithm (3), (6): Figure 3, the step count, and its order."""
import math

import numpy as np
import pytest

from pendulab import cases
from pendulab.errors import InputError
from pendulab.taylor import simulate, step_count

# Figure 3 of the coursework: l = 1, alpha = pi/4, h = 0.1, 12 significant digits.
FIGURE3 = {
    0: (0.0, 0.785398163397, 0.0),
    1: (0.1, 0.750726419819, -0.693434871572),
    2: (0.2, 0.647933915928, -1.33755362818),
    3: (0.3, 0.484585008774, -1.87713178299),
    18: (1.8, 0.569659507564, 1.6947608797),
    19: (1.9, 0.712689739829, 1.09586683808),
    20: (2.0, 0.790214993286, 0.413982837259),
    21: (2.1, 0.796774928412, -0.297068336875),
}


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


def plain_python_taylor(alpha, c, h, n):
    """Equations (3) written out again, independently of the kernel."""
    z1, z2 = [alpha], [0.0]
    for i in range(n):
        z1.append(z1[i] + h * z2[i] + h**2 / 2 * c * math.sin(z1[i]))
        z2.append(z2[i] + h * c * math.sin(z1[i]) + h**2 / 2 * c * z2[i] * math.cos(z1[i]))
    return np.array(z1), np.array(z2)


def test_kernel_agrees_with_plain_python():
    tr = simulate(2.08, 4 * math.pi / 5, 0.01, 10.0, t0=1.0)
    z1, z2 = plain_python_taylor(4 * math.pi / 5, -9.80665 / 2.08, 0.01, 900)
    assert np.allclose(tr.theta, z1, rtol=0, atol=1e-13)
    assert np.allclose(tr.omega, z2, rtol=0, atol=1e-13)
    assert tr.t[0] == 1.0 and tr.t[-1] == pytest.approx(10.0)


@pytest.mark.parametrize("t0, t_max, h, n", [(0, 2.1, 0.1, 21), (0, 1, 0.3, 3), (0, 1, 0.4, 2), (1, 2, 1e-3, 1000)])
def test_step_count_is_round_of_equation_6(t0, t_max, h, n):
    assert step_count(t0, t_max, h) == n


def test_global_error_is_second_order_against_scipy():
    # Reference trajectory: scipy's DOP853 at tight tolerance (an independent integrator).
    from scipy.integrate import solve_ivp

    l, alpha, g = 3.5, math.pi / 4, 9.80665
    sol = solve_ivp(lambda t, y: [y[1], -g / l * math.sin(y[0])], (0, 4), [alpha, 0.0],
                    method="DOP853", rtol=1e-13, atol=1e-13, dense_output=True)
    steps = [0.02, 0.01, 0.005, 0.0025]
    errors = []
    for h in steps:
        tr = simulate(l, alpha, h, 4.0)
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


def test_canonical_cases_are_the_spec_values():
    assert cases.FIGURE3.l == 1.0 and cases.FIGURE3.alpha == math.pi / 4
    assert cases.PROBLEM4.l == 3.5 and cases.PROBLEM5.alpha == 4 * math.pi / 5
    assert cases.G == 9.80665


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
