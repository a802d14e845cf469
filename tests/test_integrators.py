"""The integrators behind step(): taylor2 bit for bit, and the measured order of each method."""
import math

import numpy as np
import pytest

from pendulab.core import methods
from pendulab.core.errors import InputError
from pendulab.numerics.crossing import estimate_period
from pendulab.numerics.motion import exact_motion, global_error
from pendulab.numerics.period import agm_period
from pendulab.numerics.simulation import method_code, simulate
from reference import EXAMPLE_LENGTH, G, taylor2_plain


def test_taylor2_is_bit_identical_to_equations_3():
    # The coursework program taylor.py (a plain loop of (3)): the kernel must match bit for bit.
    alpha, h, c = 4 * math.pi / 5, 0.2, -G / EXAMPLE_LENGTH
    z1, z2 = taylor2_plain(alpha, c, h, 60)
    tr = simulate(EXAMPLE_LENGTH, alpha, h, 12.0)
    assert tr.theta.tolist() == z1.tolist()
    assert tr.omega.tolist() == z2.tolist()


def test_figure3_last_row():
    # Figure 3 of the coursework: t = 2.1 -> z1 = 0.796774928412, z2 = -0.297068336875 (12 digits).
    tr = simulate(1, math.pi / 4, 0.1, 2.1, method="taylor2")
    assert f"{tr.theta[-1]:.12g}" == "0.796774928412"
    assert f"{tr.omega[-1]:.12g}" == "-0.297068336875"


def test_general_taylor_of_order_2_is_equations_3():
    a = simulate(1, 1.0, 0.05, 5.0, method="taylor2")
    b = simulate(1, 1.0, 0.05, 5.0, method="taylor:2")
    assert np.max(np.abs(a.theta - b.theta)) < 1e-13


def test_taylor_order_1_is_euler():
    h, c = 0.01, -G
    z1, z2 = 1.0, 0.0
    for _ in range(100):
        z1, z2 = z1 + h * z2, z2 + h * c * math.sin(z1)
    tr = simulate(1, 1.0, h, 1.0, method="taylor:1")
    assert tr.theta[-1] == pytest.approx(z1, abs=1e-14)
    assert tr.omega[-1] == pytest.approx(z2, abs=1e-13)


def _steps(order: int) -> list[float]:
    """Steps where the global error of a method of ``order`` is in its asymptotic regime and
    far above rounding (above 1e-11 at the finest)."""
    if order == 1:
        return [0.004, 0.002, 0.001, 0.0005]
    if order <= 3:
        return [0.04, 0.02, 0.01, 0.005]
    if order <= 5:
        return [0.08, 0.04, 0.02, 0.01]
    return [0.12, 0.1, 0.08, 0.06]


#: Every method of the registry's menu, and the Taylor family at a few orders: the order
#: each states is the one measured.
ORDER_CASES = [methods.menu(), [methods.resolve(f"taylor:{p}") for p in (1, 3, 5, 8)]]


@pytest.mark.parametrize("method", [m for group in ORDER_CASES for m in group], ids=lambda m: m.name)
def test_measured_order(method):
    """Log-log slope of the global error max_j |z1_j - theta(t_j)| on [0, 2.4] against h."""
    order, steps, method = method.order, _steps(method.order), method.name
    assert method_code(method)[1] == order
    errors = []
    for h in steps:
        tr = simulate(1.0, 1.0, h, 2.4, method=method)
        ge = global_error(tr)
        errors.append(ge.max_theta_error)  # exact motion as reference (tested against mpmath)
    assert min(errors) > 1e-11  # away from rounding
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert abs(slope - order) < 0.2, (method, slope)


def test_rk4_against_scipy_dop853_reference():
    # Cross-check with scipy's solve_ivp (DOP853, tight tolerances) rather than our exact motion.
    from scipy.integrate import solve_ivp

    tr = simulate(0.7, 2.0, 0.001, 3.0, method="rk4")
    sol = solve_ivp(lambda t, y: [y[1], -G / 0.7 * math.sin(y[0])], (0, 3.0), [2.0, 0.0],
                    method="DOP853", rtol=1e-13, atol=1e-13, t_eval=[3.0])
    assert tr.theta[-1] == pytest.approx(sol.y[0, -1], abs=1e-10)
    assert tr.omega[-1] == pytest.approx(sol.y[1, -1], abs=1e-9)


def test_verlet_energy_stays_bounded():
    """Stormer-Verlet is symplectic: no energy drift over 50 periods; taylor2's grows."""
    alpha, h = 2.0, 0.02
    T = agm_period(1.0, alpha)
    drift = {}
    for method in ("verlet", "taylor2"):
        ge = global_error(simulate(1.0, alpha, h, 50 * T, method=method))
        n = len(ge.t) // 50
        drift[method] = (np.max(np.abs(ge.energy_drift[:n])), np.max(np.abs(ge.energy_drift[-n:])))
    first, last = drift["verlet"]
    assert last < 1.5 * first  # bounded oscillation
    first, last = drift["taylor2"]
    assert last > 10 * first  # secular growth


@pytest.mark.parametrize("method", ["taylor2", "rk4", "verlet", "taylor:6"])
def test_period_estimator_works_with_every_method(method):
    est = estimate_period(1.0, math.pi / 3, 1e-2, method=method)
    assert est.method == method
    order = method_code(method)[1]
    # Error ~ C h^min(order, 4): the method's, or the cubic interpolation's (order 4); C = 10.
    assert est.cubic_error < 10 * 1e-2 ** min(order, 4)


def test_high_order_taylor_step_is_exact_to_rounding():
    tr = simulate(1.0, 2.5, 0.05, 1.0, method="taylor:20")
    ex = exact_motion(1.0, 2.5, tr.t)
    assert np.max(np.abs(tr.theta - ex.theta)) < 1e-13


def test_methods_registry_and_bad_names():
    assert [(m.name, method_code(m.name)) for m in methods.menu()] == [("taylor2", (0, 2)), ("rk4", (1, 4)),
                                                                        ("verlet", (2, 2))]
    assert method_code("taylor:7") == (3, 7)
    for bad in ("taylor:0", "taylor:-1", "taylor:31", "taylor:", "taylor:2.5", "euler", "RK4"):
        with pytest.raises(InputError, match=r"method = .* taylor2, rk4, verlet, taylor:P"):
            method_code(bad)
    with pytest.raises(InputError, match="method"):
        simulate(1, 1.0, 0.1, 1.0, method="taylor:0")
