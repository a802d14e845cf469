"""The period from a simulation: sign change, linear and inverse cubic estimates."""
import math
import re

import numpy as np
import pytest

from pendulab.crossing import estimate_period, observed_orders
from pendulab.errors import InputError, LeftOscillationError, NoReturnError
from pendulab.period import agm_period
from pendulab.taylor import simulate

L3 = 2.0800838231  # problem 3(b), the spec's example group
A3 = 4 * math.pi / 5


def test_streamed_search_equals_search_on_the_stored_trajectory():
    h = 1e-3
    est = estimate_period(L3, A3, h)
    tr = simulate(L3, A3, h, 6.0)
    z1, z2 = tr.theta, tr.omega
    j = next(i for i in range(len(z2) - 1) if z2[i] > 0 >= z2[i + 1] and z1[i + 1] > 0)
    assert est.j == j
    assert np.array_equal(est.window_omega, z2[j - 2 : j + 3])
    assert np.array_equal(est.window_theta, z1[j - 2 : j + 3])
    assert est.bracket == (pytest.approx(j * h, abs=1e-12), pytest.approx((j + 1) * h, abs=1e-12))


def test_estimates_lie_in_the_bracket_and_near_the_exact_period():
    for h in (1e-2, 1e-3, 1e-4):
        est = estimate_period(L3, A3, h)
        lo, hi = est.bracket
        assert lo <= est.linear <= hi
        assert lo <= est.cubic <= hi
        # The Taylor method's period error is O(h^2): below h^2 here (0.3 h^2 to 0.7 h^2).
        assert est.cubic_error < h * h


def test_period_error_is_second_order():
    steps = [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4]
    errors = [estimate_period(L3, A3, h).cubic_error for h in steps]
    slope = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert abs(slope - 2) < 0.15
    orders = observed_orders(steps, errors)
    assert orders[0] is None and all(abs(o - 2) < 0.25 for o in orders[2:])


def test_interpolation_error_is_negligible_next_to_taylor_error_at_1e3():
    # Problem 3(d): with h = 1e-3 the cubic's interpolation error is ~1e-15, the
    # Taylor method's error ~6e-7 (both measured against the exact period).
    est = estimate_period(L3, A3, 1e-3)
    assert abs(est.cubic_error_estimate) < 1e-12
    assert est.cubic_error > 1e4 * abs(est.cubic_error_estimate)


def test_cubic_recovers_the_zero_of_a_smooth_trajectory():
    # With an accurate trajectory (tiny step), p(0) is the period to ~1e-12.
    est = estimate_period(1.0, math.pi / 4, 1e-5)
    assert est.cubic == pytest.approx(agm_period(1.0, math.pi / 4), abs=1e-9)


def test_figure2_bracket():
    # Figure 2: for l = 1, alpha = pi/4, h = 0.1 the period is in (2.0, 2.1).
    est = estimate_period(1.0, math.pi / 4, 0.1, t_max=2.3)
    assert est.bracket == (pytest.approx(2.0), pytest.approx(2.1))


def test_no_return_names_a_t_max_that_works():
    with pytest.raises(NoReturnError) as err:
        estimate_period(L3, A3, 1e-2, t_max=3.0)
    suggested = float(re.search(r"--t-max ([0-9.e+-]+)", str(err.value)).group(1))
    assert estimate_period(L3, A3, 1e-2, t_max=suggested).cubic > 3.0


def test_going_over_the_top_is_reported():
    with pytest.raises(LeftOscillationError, match="over the top"):
        estimate_period(L3, 3.0, 0.5)


@pytest.mark.parametrize(
    "kwargs, name",
    [({"amplitude": 0.0}, "amplitude"), ({"step": 0}, "step"), ({"step": 10.0, "t_max": 5.0}, "step"),
     ({"t_max": -2}, "t_max"), ({"length": -3}, "length"), ({"method": "nope"}, "method")],
)
def test_bad_input(kwargs, name):
    args = {"length": 1.0, "amplitude": 1.0, "step": 1e-2} | kwargs
    with pytest.raises(InputError) as err:
        estimate_period(**args)
    assert err.value.name == name
