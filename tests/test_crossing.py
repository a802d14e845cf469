"""The period from a simulation: sign change, linear and inverse cubic estimates."""
import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.core.errors import InputError, LeftOscillationError, NoReturnError, NumericalError
from pendulab.core.methods import Status
from pendulab.numerics.crossing import estimate_period, observed_orders, search_period, untrusted
from pendulab.numerics.period import agm_period
from pendulab.numerics.simulation import simulate
from reference import EXAMPLE_LENGTH, G, reference_period, taylor2_plain

L3 = EXAMPLE_LENGTH  # problem 3(b), the spec's example group
A3 = 4 * math.pi / 5


@pytest.mark.slow
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
    suggested = float(re.search(r"t_max = ([0-9.e+-]+) s holds the return", str(err.value)).group(1))
    assert estimate_period(L3, A3, 1e-2, t_max=suggested).cubic > 3.0
    # The same as data: the interval searched and one that holds the return.
    assert err.value.t_max == 3.0 and f"{err.value.suggested_t_max:.4g}" == f"{suggested:.4g}"
    assert estimate_period(L3, A3, 1e-2, t_max=err.value.suggested_t_max).cubic > 3.0


@pytest.mark.parametrize("amplitude, step", [(3.0, 0.5), (3.1, 0.2), (2.6, 0.9)])
def test_going_over_the_top_is_reported_with_its_time(amplitude, step):
    with pytest.raises(LeftOscillationError, match="over the top") as err:
        estimate_period(L3, amplitude, step)
    # The time it carries is the first point of the simulation with |theta| > pi.
    tr = simulate(L3, amplitude, step, err.value.t + step)
    over = np.flatnonzero(np.abs(tr.theta) > math.pi)
    assert over.size and tr.t[over[0]] == err.value.t


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


# ------------------------------------------------------------------ the edges: tiny amplitudes, dense output
@pytest.mark.parametrize("method", ["taylor2", "rk4", "taylor:8"])
def test_tiny_amplitudes_give_the_small_amplitude_estimates_bit_for_bit(method):
    # Below 2^-30, sin(z) = z and cos(z) = 1 in doubles: the simulation is linear and
    # scales by the power of two exactly, so the estimates must be the same bits
    # (at 1e-160 the divided differences of theta' overflow unless scaled: -inf and NaN).
    ref = estimate_period(1.0, 2.0**-30, 1e-3, method=method)
    for e in (-500, -1000):
        est = estimate_period(1.0, 2.0**e, 1e-3, method=method)
        assert est.j == ref.j
        assert (est.linear, est.cubic, est.dense) == (ref.linear, ref.cubic, ref.dense)
        assert est.cubic_error_estimate == ref.cubic_error_estimate
        assert est.interpolation.rounding_level == ref.interpolation.rounding_level
    assert ref.cubic_error < 1e-5 and math.isfinite(ref.cubic_error_estimate)


def test_amplitude_1e_160_is_estimated():
    est = estimate_period(1.0, 1e-160, 1e-3)
    assert math.isfinite(est.cubic) and math.isfinite(est.cubic_error_estimate)
    # The period of a 1e-160 rad swing is 2 pi sqrt(l/g) to 1e-320: the cubic is within
    # the O(h^2) error of (3), as at any small amplitude.
    assert abs(est.cubic - 2 * math.pi / math.sqrt(G)) < 1e-5


def test_sweep_finds_tiny_amplitudes_with_finite_errors():
    from pendulab.jobs.sweep import sweep

    r = sweep(np.array([1e-200, 1e-160, 1e-3]), [1e-3])
    assert list(r["status"]) == ["found"] * 3
    assert np.all(np.isfinite(r["cubic_signed_error"])) and np.all(np.abs(r["cubic_signed_error"]) < 1e-5)
    assert r.summary()[0]["max_abs_cubic_error"] < 1e-5


def test_subnormal_amplitude_says_why_not_t_max():
    with pytest.raises(NoReturnError) as err:
        estimate_period(1.0, 5e-324, 1e-3)
    msg = str(err.value)
    assert "underflow" in msg and "--t-max" not in msg and "no t_max helps" in msg


def test_dense_estimate_reaches_the_method_order():
    import mpmath

    from reference import period_mp

    period = float(period_mp(EXAMPLE_LENGTH, 4 * math.pi / 5, dps=30))  # the double 4pi/5, mpmath AGM
    # taylor:8: the cubic stops at O(h^4), the dense estimate keeps going (slope ~8).
    hs = [0.1, 0.05]
    dense = [abs(estimate_period(EXAMPLE_LENGTH, 4 * math.pi / 5, h, method="taylor:8").dense - period) for h in hs]
    cubic = [abs(estimate_period(EXAMPLE_LENGTH, 4 * math.pi / 5, h, method="taylor:8").cubic - period) for h in hs]
    slope = math.log(dense[0] / dense[1]) / math.log(2)
    assert 7 < slope < 10.5, slope
    assert dense[1] < cubic[1] / 1000
    # taylor:12 at h = 0.1: 4e-6 by the cubic, 3e-13 by the dense output (measured).
    est = estimate_period(EXAMPLE_LENGTH, 4 * math.pi / 5, 0.1, method="taylor:12")
    assert abs(est.dense - period) < 1e-12 < 1e-6 < abs(est.cubic - period)
    # taylor2: both estimates carry the method's O(h^2) error, and agree to it.
    est = estimate_period(EXAMPLE_LENGTH, 4 * math.pi / 5, 1e-3)
    assert abs(est.dense - est.cubic) < 1e-8
    assert mpmath  # mpmath's AGM is the reference above


@pytest.mark.slow
def test_flow_series_is_the_solution_of_the_ode():
    import mpmath

    from pendulab.numerics.dense import flow_series, series_zero

    c, z1, z2 = -G / EXAMPLE_LENGTH, 2.4, 0.3
    x = flow_series(z1, z2, c)
    # Reference: mpmath's own Taylor-series ODE solver at 30 digits, independent of the recurrence.
    with mpmath.workdps(30):
        sol = mpmath.odefun(lambda t, y: [y[1], c * mpmath.sin(y[0])], 0, [mpmath.mpf(z1), mpmath.mpf(z2)])
        for s in (0.01, 0.05):
            theta, omega = sol(s)
            assert sum(xk * s**k for k, xk in enumerate(x)) == pytest.approx(float(theta), abs=1e-15)  # 2 ulps
            assert sum(k * xk * s ** (k - 1) for k, xk in enumerate(x) if k) == pytest.approx(float(omega), abs=4e-16)
        # The zero of theta' (the top of the swing) by Newton on the series, against mpmath's root.
        s = series_zero(x, 0.0, 0.0, 0.1)
        ref = mpmath.findroot(lambda t: sol(t)[1], 0.02)
        assert s == pytest.approx(float(ref), abs=1e-16)


def plain_first_return(alpha, h, t_max, length=1.0):
    """j of the coursework's own program (3) in plain Python doubles, subnormals included."""
    from plain_pendulum import problem3, taylor

    _, z1, z2 = taylor.taylor(length, alpha, h, t_max)
    return problem3.sign_change(z1, z2)[0]


def _subnormal_walk():
    """alpha from 1e-300 down to the smallest subnormal: decades, then multiples of 2^-1074
    around the last that moves at h = 1e-3 (h (g/l) alpha = 2^-1075 between 50 and 51 of them)."""
    tiny = 5e-324
    return [10.0**-e for e in (300, 306, 308, 310, 315, 318, 320, 321)] + [n * tiny for n in (200, 100, 52, 51, 50, 49, 20, 1)]


@pytest.mark.slow  # plain (3) in Python over 16 amplitudes: 5 s
def test_the_underflow_refusal_is_where_plain_3_never_returns():
    # Plain (3) in doubles returns with subnormal theta' steps (j = 2006 down to 1e-315, then
    # other j as the steps quantise); it never moves once h (g/l) alpha rounds to zero.
    for alpha in _subnormal_walk():
        s = search_period(1.0, alpha, 1e-3)
        j = plain_first_return(alpha, 1e-3, s.t_max)
        assert (s.estimate.j if s.found else None) == j, alpha
        assert s.underflow == (j is None), alpha
        if s.underflow:
            assert s.suggested_t_max is None and s.moving_amplitude == pytest.approx(5e-324 / (1e-3 * G) / 2)
            # No t_max helps: the first step of (3) leaves the state where it is.
            assert plain_first_return(alpha, 1e-3, 100 * s.t_max) is None
    assert search_period(1.0, 1e-320, 1e-3).found and search_period(1.0, 49 * 5e-324, 1e-3).underflow


def test_sweep_and_estimate_agree_where_theta_prime_is_subnormal():
    from pendulab.jobs.sweep import sweep

    alphas = np.array(_subnormal_walk() + [1e-3])
    r = sweep(alphas, [1e-3])
    for a, status, cubic in zip(alphas, r["status"], r["cubic"]):
        s = search_period(1.0, float(a), 1e-3)
        assert status == s.status.name.lower(), a
        assert (cubic == s.estimate.cubic) if s.found else np.isnan(cubic), a
    with pytest.raises(NoReturnError, match="no t_max helps"):
        estimate_period(1.0, 49 * 5e-324, 1e-3)


# --- failure as data: search_period's status and its numbers ---------------------------------


def test_search_finds_what_estimate_period_returns():
    s = search_period(1.0, 0.5, 1e-3)
    e = estimate_period(1.0, 0.5, 1e-3)
    assert s.status == Status.FOUND and s.found and s.estimate is not None
    assert (s.estimate.j, s.estimate.bracket, s.estimate.cubic, s.estimate.linear) == (e.j, e.bracket, e.cubic, e.linear)
    assert s.period == e.period and s.t_left is None and s.suggested_t_max is None
    assert s.to_dict()["estimate"]["cubic"] == e.cubic


def test_over_the_top_is_a_status_with_the_time_of_the_plain_loop():
    length, alpha, h = 1.0, 3.0, 0.5
    s = search_period(length, alpha, h)
    assert s.status == Status.LEFT_OSCILLATION and s.estimate is None and not s.found
    # The coursework's plain loop of (3): the first point with |theta| >= pi.
    z1, _ = taylor2_plain(alpha, -G / length, h, int(round(s.t_max / h)))
    first = int(np.argmax(np.abs(z1) >= math.pi))
    assert abs(z1[first]) >= math.pi and s.t_left == first * h
    with pytest.raises(LeftOscillationError) as info:
        estimate_period(length, alpha, h)
    assert info.value.t == s.t_left


def test_no_return_is_a_status_with_a_t_max_that_holds_the_return():
    s = search_period(1.0, 1.0, 1e-2, t_max=1.0)
    assert s.status == Status.NO_RETURN and s.estimate is None and not s.underflow
    assert s.t_max == 1.0 and s.suggested_t_max is not None and s.suggested_t_max > s.period
    assert search_period(1.0, 1.0, 1e-2, t_max=s.suggested_t_max).found
    with pytest.raises(NoReturnError) as info:
        estimate_period(1.0, 1.0, 1e-2, t_max=1.0)
    assert (info.value.t_max, info.value.suggested_t_max) == (s.t_max, s.suggested_t_max)


def test_an_underflowing_motion_is_no_return_that_no_t_max_helps():
    s = search_period(1.0, 1e-320, 1e-6, t_max=1.0)  # h (g/l) alpha ~ 1e-325 rounds to zero: it never moves
    assert s.status == Status.NO_RETURN and s.underflow and s.suggested_t_max is None and s.j is None
    with pytest.raises(NoReturnError, match="no t_max helps"):
        estimate_period(1.0, 1e-320, 1e-6, t_max=1.0)


_EDGE = st.sampled_from([0.0, -0.0, 5e-324, -5e-324, 1.0, -1.0, math.pi, -math.pi, math.nextafter(math.pi, 0),
                         -math.nextafter(math.pi, 0), math.inf, -math.inf, math.nan])
_ANY = st.one_of(_EDGE, st.floats(-4.0, 4.0))


@settings(max_examples=300, deadline=None)
@given(z1=_ANY, z1n=_ANY, z2=_ANY, z2n=_ANY, i=st.integers(0, 6), n=st.integers(1, 8))
def test_return_rule_decides_as_the_coursework_program(z1, z1n, z2, z2n, i, n):
    # The one statement of the first-return rule (the scalar search and the sweep's lanes
    # both call it) against the coursework program problem3.py's sign_change on the two
    # points Z_i, Z_{i+1}, and the window Z_{j-2} .. Z_{j+2} that the estimate needs.
    from pendulab.engine.kernels import FOUND, LEFT_OSCILLATION, NO_RETURN, TOO_EARLY, UNDECIDED, return_rule
    from pendulab.jobs.coursework import load

    j, over = load()["problem3.py"].sign_change([z1, z1n], [z2, z2n])
    if over is not None or math.isnan(z1n):  # a NaN angle (a blow-up) is over the top too
        expected = (LEFT_OSCILLATION, i)
    elif j is None:
        expected = (UNDECIDED, i)
    elif i < 2:
        expected = (TOO_EARLY, i)  # no Z_{j-2}
    elif i + 2 > n:
        expected = (NO_RETURN, n)  # Z_{j+2} beyond the n steps
    else:
        expected = (FOUND, i)
    assert return_rule(i, n, z1n, z2, z2n) == expected


def test_subnormal_steps_whose_nodes_coincide_are_a_status():
    # 5e-324 at h = 0.25: theta' moves by a few subnormals a step and returns (plain (3) too),
    # but two of the five z2 around the sign change are equal: no inverse cubic through them.
    from pendulab.jobs.sweep import sweep

    s = search_period(1.0, 5e-324, 0.25)
    assert s.status == Status.NODES_COINCIDE and s.estimate is None and not s.underflow
    assert plain_first_return(5e-324, 0.25, s.t_max) == s.j
    with pytest.raises(NumericalError, match="subnormal steps"):
        estimate_period(1.0, 5e-324, 0.25)
    assert list(sweep(np.array([5e-324]), [0.25])["status"]) == ["nodes_coincide"]


# ---------------------------------------------------------------------------- trust near the separatrix
def mp_window_drift(s):
    """``max |E(z1_k, z2_k) - E(alpha, 0)|`` over the window and ``2 (g/l) cos^2(alpha/2)``, in mpmath
    at 60 digits from the exact doubles (``E = z2^2/2 - (g/l) cos(z1)``)."""
    import mpmath

    e = s.estimate
    with mpmath.workdps(60):
        w2 = mpmath.mpf(s.g) / mpmath.mpf(s.length)
        e0 = -w2 * mpmath.cos(mpmath.mpf(s.amplitude))
        drift = max(abs(mpmath.mpf(z2) ** 2 / 2 - w2 * mpmath.cos(mpmath.mpf(z1)) - e0)
                    for z1, z2 in zip(e.window_theta, e.window_omega))
        return float(drift), float(2 * w2 * mpmath.cos(mpmath.mpf(s.amplitude) / 2) ** 2)


@pytest.mark.parametrize("method", ["rk4", "verlet", "taylor:4"])
@pytest.mark.parametrize("gap", [1e-12, 1e-9])
def test_near_pi_a_return_that_cannot_be_trusted_is_a_status(method, gap):
    """Issue 32: within 1e-9 of pi the estimates are 13-56 % off while the energy error exceeds
    the distance to the separatrix; the search says so, with its numbers."""
    from pendulab.core.errors import UntrustedError
    from pendulab.jobs.sweep import sweep

    alpha = math.pi - gap
    s = search_period(1.0, alpha, 1e-3, method=method)
    assert s.status == Status.UNTRUSTED and not s.found and s.estimate is not None
    drift, distance = mp_window_drift(s)
    assert s.max_energy_drift == pytest.approx(drift, rel=1e-6) and drift > distance
    assert s.separatrix_distance == pytest.approx(distance, rel=1e-12)
    period = float(reference_period(1.0, alpha))
    assert abs(s.estimate.cubic - period) > 0.1 * period  # what the status warns of
    with pytest.raises(UntrustedError, match="cannot be trusted near the separatrix") as err:
        estimate_period(1.0, alpha, 1e-3, method=method)
    assert err.value.max_energy_drift == s.max_energy_drift
    if method == "rk4":
        assert list(sweep(np.array([alpha]), [1e-3], methods=[method])["status"]) == ["untrusted"]


def test_far_from_pi_a_return_is_trusted():
    """The coursework's pendulum (problem 3(d)): the energy error far inside the distance."""
    s = search_period(EXAMPLE_LENGTH, 4 * math.pi / 5, 1e-3)
    drift, distance = mp_window_drift(s)
    assert s.status == Status.FOUND and s.max_energy_drift == pytest.approx(drift, rel=1e-6)
    assert drift < 1e-3 * distance and s.separatrix_distance == pytest.approx(distance, rel=1e-12)


def test_a_quarter_period_off_is_untrusted():
    assert untrusted(0.0, 1.0, 1.26, 1.0) and not untrusted(0.0, 1.0, 1.24, 1.0)
    assert untrusted(2.0, 1.0, 1.0, 1.0) and not untrusted(1.0, 1.0, 1.0, 1.0)


# ---------------------------------------------------------------------------- the dense crossing's bound
@pytest.mark.parametrize("method", ["taylor2", "rk4", "taylor:8"])
def test_dense_crossing_within_its_bound_as_estimate_period_calls_it(method):
    """search_period's (estimate_period's) dense estimate against the exact flow through its own bracket point
    (taken at the real time j h: benchmarks/adversarial.py, turning_time), over the steps callers
    type and amplitudes from 0.3 to pi - 1e-6: the worst within crossing_bound (roundings of
    t_j = j h and of t_j + s included)."""
    import sys
    from pathlib import Path

    import mpmath

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    import adversarial

    from pendulab.numerics.dense import crossing_bound

    worst = 0.0
    for length, alpha in [(EXAMPLE_LENGTH, 4 * math.pi / 5), (0.3, 0.3), (25.0, 2.9), (1.0, math.pi - 1e-6)]:
        c, w = -G / length, math.sqrt(G / length)
        for h in (0.1, 0.02, 1e-2, 1e-3):
            if w * h > 0.4:
                continue
            e = search_period(length, alpha, h, method=method).estimate  # an untrusted return too
            if e is None:  # over the top: no bracket
                continue
            (z1a, z1b), (z2a, z2b) = e.window_theta[2:4], e.window_omega[2:4]
            with mpmath.workdps(60):
                ta = mpmath.mpf(e.j) * h
                if z2a / (z2a - z2b) <= 0.5:
                    ref = ta + adversarial.turning_time(z1a, z2a, c, True)
                else:
                    ref = ta + h - adversarial.turning_time(z1b, z2b, c, False)
                worst = max(worst, float(abs(e.dense - ref)) / crossing_bound(e.dense, w, h))
    assert worst <= 1.0
