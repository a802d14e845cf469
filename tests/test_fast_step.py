"""The certified fast step of (3) (pendulab.engine.kernels.taylor2_fast_step) equals the literal one bit for bit.

``taylor2_fast_step`` takes ``sin`` and ``cos`` from a table (:mod:`pendulab.engine.fast`) and
returns its own result only where a rounding test proves it equal to
:func:`pendulab.engine.kernels.taylor2_step` with the C library's functions. These tests check the
table and its error against mpmath and the C library (the margins the test relies on, with
a safety factor), the points of the driver and the period search under both kernel codes
against the literal loop over many pendulums and steps, that the fallback is taken, and
that the library's runs take the fast code where :func:`pendulab.engine.kernels.kernel_code` says.
"""
import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numba import njit

from pendulab.core.methods import Status
from pendulab.engine import kernels
from pendulab.engine.fast import FAST_COS, FAST_MAX_K, FAST_SIN, certified_step, margins, table_sin_cos
from pendulab.engine.kernels import (
    FOUND,
    RK4,
    TAYLOR2,
    TAYLOR2_FAST,
    drive,
    first_return,
    kernel_code,
    taylor2_fast_step,
    taylor2_step,
)
from pendulab.engine.libm import cos, sin
from reference import EXAMPLE_LENGTH, G

#: The margins must exceed the table's distance from the C library's values (plus half an
#: ulp for the rounding of ``s +- ds``) by this factor at least.
SAFETY = 4


@njit
def _worst_fraction_of_margin(x):
    """The largest ``|table - C library| / margin`` over ``x``, for sin and for cos (the
    margins taken at the C library's values)."""
    ws = wc = 0.0
    for i in range(x.size):
        s, co = table_sin_cos(x[i])
        gs, gc = sin(x[i]), cos(x[i])
        ms, mc = margins(x[i], gs, gc)
        ws = max(ws, (abs(s - gs) + 0.5 * 2.0**-52 * abs(gs)) / ms)
        wc = max(wc, (abs(co - gc) + 0.5 * 2.0**-52 * abs(gc)) / mc)
    return ws, wc


def _angles(n, seed):
    """Angles in (-pi, pi): uniform, near 0 (down to subnormal), near pi/2 and pi, at the table's nodes."""
    rng = np.random.default_rng(seed)
    near_pi = np.nextafter(math.pi, 0) - np.abs(rng.standard_normal(n // 10)) * 10.0 ** rng.uniform(-16, -1, n // 10)
    tiny = 10.0 ** rng.uniform(-320, 0, n // 10)
    half = math.pi / 2 + rng.uniform(-1e-3, 1e-3, n // 10)
    nodes = (np.arange(0, 805) / 256.0)[:, None] + np.array([-1 / 512, 1 / 512, 0.0, -1e-12, 1e-12])[None, :]
    x = np.concatenate([rng.uniform(0, math.pi, n), near_pi, tiny, half, nodes.ravel(),
                        [0.0, 5e-324, 2.0**-1022, np.nextafter(math.pi, 0)]])
    x = x[np.abs(x) < math.pi]
    return np.concatenate([x, -x])


def test_table_is_the_nearest_double_to_sin_and_cos():
    assert FAST_SIN.shape == FAST_COS.shape == (806,)
    with mpmath.workdps(40):
        for k in range(806):
            y = mpmath.mpf(k) / 256
            assert FAST_SIN[k] == float(mpmath.sin(y)), k
            assert FAST_COS[k] == float(mpmath.cos(y)), k


@pytest.mark.slow
def test_table_sin_cos_within_a_quarter_of_the_margins_of_the_c_library():
    """10^6 angles (more in benchmarks): the certificate's premise, with a factor SAFETY to spare."""
    ws, wc = _worst_fraction_of_margin(_angles(1_000_000, 1))
    assert ws <= 1 / SAFETY and wc <= 1 / SAFETY, (ws, wc)


@pytest.mark.slow
def test_table_sin_cos_error_against_mpmath():
    """Against the true values: within an eighth of the margins (the C library adds below 1 ulp)."""
    x = _angles(2000, 2)[::5]
    with mpmath.workdps(40):
        for v in x:
            s, co = table_sin_cos(v)
            ts, tc = mpmath.sin(mpmath.mpf(v)), mpmath.cos(mpmath.mpf(v))
            ms, mc = margins(v, float(ts), float(tc))
            assert abs(mpmath.mpf(s) - ts) <= ms / (2 * SAFETY), v
            assert abs(mpmath.mpf(co) - tc) <= mc / (2 * SAFETY), v


@njit
def _compare_steps(alpha, c, h, n):
    """Walk ``n`` literal steps from ``(alpha, 0)``; at each, the fast step must give the same bits.

    Returns ``(mismatches, fallbacks, steps run)``: a fallback is a step whose rounding test
    failed (the fast step then takes the literal one).
    """
    z1, z2 = alpha, 0.0
    bad = fallbacks = 0
    i = 0
    K = 0.5 * h * h * c
    while i < n and abs(z1) < math.pi:
        a, b = taylor2_step(z1, z2, h, c)
        f1, f2 = taylor2_fast_step(z1, z2, h, c)
        if not (a == f1 and b == f2 and math.copysign(1.0, a) == math.copysign(1.0, f1)
                and math.copysign(1.0, b) == math.copysign(1.0, f2)):
            bad += 1
        if abs(K) <= FAST_MAX_K and not certified_step(z1, z2, h, c, K)[0]:
            fallbacks += 1
        z1, z2 = a, b
        i += 1
    return bad, fallbacks, i


def _python_loop(alpha, c, h, n):
    """(3) with math.sin and math.cos, in the kernel's order of operations (NaN from inf on)."""
    z1, z2 = [alpha], [0.0]
    for _ in range(n):
        a, b = z1[-1], z2[-1]
        finite = math.isfinite(a)
        s = math.sin(a) if finite else math.nan
        z1.append(a + h * b + 0.5 * h * h * c * s)
        z2.append(b + h * c * s + 0.5 * h * h * c * b * (math.cos(a) if finite else math.nan))
    return np.array(z1), np.array(z2)


@pytest.mark.slow
@pytest.mark.parametrize("alpha", [1e-8, 1e-3, 0.5, 4 * math.pi / 5, 3.1, math.pi - 1e-9])
@pytest.mark.parametrize("c", [-1e-3, -G / EXAMPLE_LENGTH, -1e3])
def test_fast_step_equals_the_literal_step_along_trajectories(alpha, c):
    total_fallbacks = 0
    for h in (1e-7, 1e-6, 1e-5, 1e-3, 0.5):
        for sign in (1.0, -1.0):
            hs = sign * h / math.sqrt(-c)  # the same dimensionless steps for every c
            bad, fallbacks, _ = _compare_steps(alpha, c, hs, 200_000)
            assert bad == 0, (alpha, c, hs)
            total_fallbacks += fallbacks
    assert total_fallbacks > 0  # the rounding test does fail sometimes: the fallback is exercised


@pytest.mark.slow
def test_fallback_rate_at_problem_3():
    """About 1 step in 10^3 falls back at h = 1e-6 (the README's figure), and the points stay exact."""
    c = -G / EXAMPLE_LENGTH
    bad, fallbacks, steps = _compare_steps(4 * math.pi / 5, c, 1e-6, 3_000_000)
    assert bad == 0 and steps == 3_000_000
    assert 1e-4 < fallbacks / steps < 1e-2


def _same(a, b):
    """Bit for bit (``-0.0`` is not ``0.0``), any NaN equal to any NaN."""
    return bool(np.all((a.view(np.int64) == b.view(np.int64)) | (np.isnan(a) & np.isnan(b))))


@settings(max_examples=60, deadline=None)
@given(alpha=st.floats(1e-8, math.pi - 1e-9), log_h=st.floats(-7, math.log10(0.5)),
       log_c=st.floats(-3, 3), backwards=st.booleans())
def test_driver_equals_the_python_loop_under_both_codes(alpha, log_h, log_c, backwards):
    h, c = (-1 if backwards else 1) * 10.0**log_h, -(10.0**log_c)
    n = 3000
    ref1, ref2 = _python_loop(alpha, c, h, n)
    keep = np.r_[np.arange(7, n + 1, 7), n]
    for code in (TAYLOR2, TAYLOR2_FAST):
        for stride, want in ((1, np.arange(1, n + 1)), (7, keep)):
            z1, z2 = np.empty(n + 1), np.empty(n + 1)
            with np.errstate(all="ignore"):
                a, b, k = drive(code, 2, alpha, 0.0, c, h, 0, n, stride, n, z1, z2)
            assert k == len(want) and _same(z1[:k], ref1[want]) and _same(z2[:k], ref2[want]), (code, stride)
            assert _same(np.array([a, b]), np.array([ref1[n], ref2[n]]))


def test_kernel_code_chooses_the_fast_step_for_fine_steps_of_3():
    c = -G / EXAMPLE_LENGTH
    h_max = math.sqrt(2 * FAST_MAX_K / -c)  # the coarsest step the table step is tried at
    assert kernel_code(TAYLOR2, c, 1e-6) == TAYLOR2_FAST
    assert kernel_code(TAYLOR2, c, -1e-6) == TAYLOR2_FAST  # backwards in time as well
    assert kernel_code(TAYLOR2, c, math.nextafter(h_max, 0) * (1 - 1e-12)) == TAYLOR2_FAST
    assert kernel_code(TAYLOR2, c, h_max * (1 + 1e-12)) == TAYLOR2  # coarse: the test would fail too often
    assert kernel_code(TAYLOR2, c, 1e-2) == TAYLOR2
    assert kernel_code(RK4, c, 1e-6) == RK4  # another method keeps its own code
    assert kernel_code(3, c, 1e-6) == 3  # taylor:P, even P = 2


def _codes_used(monkeypatch, name):
    """Record the kernel code of every call of ``engine.kernels.<name>`` (the library's driver or search)."""
    seen = []
    kernel = getattr(kernels, name)

    def spy(code, *args):
        seen.append(code)
        return kernel(code, *args)

    monkeypatch.setattr(kernels, name, spy)
    return seen


@pytest.mark.parametrize(("h", "code"), [(1e-5, TAYLOR2_FAST), (1e-2, TAYLOR2)])
def test_the_library_runs_the_chosen_code(monkeypatch, h, code):
    """simulate (every point, thinned) and the period search run kernel_code's code, and
    simulate gives the coursework loop's points, bit for bit."""
    from pendulab.numerics import crossing, simulation

    c = -G / EXAMPLE_LENGTH
    n = 20_000
    ref1, ref2 = _python_loop(2.5, c, h, n)
    driven = _codes_used(monkeypatch, "drive")
    full = simulation.simulate(EXAMPLE_LENGTH, 2.5, h, n * h)
    assert len(full.theta) == n + 1 and _same(full.theta, ref1) and _same(full.omega, ref2)
    thin = simulation.simulate(EXAMPLE_LENGTH, 2.5, h, n * h, stride=1000)
    assert _same(thin.theta, ref1[::1000]) and _same(thin.omega, ref2[::1000])
    assert driven and set(driven) == {code}
    searched = _codes_used(monkeypatch, "search_return")
    crossing.search_period(EXAMPLE_LENGTH, 2.5, h, t_max=20 * h)
    assert searched and set(searched) == {code}


@pytest.mark.slow
@pytest.mark.parametrize(("alpha", "h"), [(4 * math.pi / 5, 1e-5), (0.3, 1e-4), (3.0, 1e-4), (1e-3, 1e-4)])
@pytest.mark.parametrize("code", [TAYLOR2, TAYLOR2_FAST])
def test_first_return_equals_the_python_loop(alpha, h, code):
    c = -G / EXAMPLE_LENGTH
    status, j, z1w, z2w = first_return(code, 2, alpha, c, h, int(10 / h))
    assert status == FOUND
    ref1, ref2 = _python_loop(alpha, c, h, j + 2)
    assert np.array_equal(z1w, ref1[j - 2:j + 3]) and np.array_equal(z2w, ref2[j - 2:j + 3])
    assert ref2[j] > 0.0 >= ref2[j + 1]


@pytest.mark.parametrize(("length", "alpha"), [(EXAMPLE_LENGTH, 4 * math.pi / 5), (0.25, 0.2), (9.0, 3.1)])
def test_period_search_with_the_fast_code_equals_the_literal_one_at_a_fine_step(monkeypatch, length, alpha):
    """search_period at h = 1e-6 (millions of steps, thousands of them through the fallback):
    the same status, the same j, the same window and the same estimates, bit for bit, with the
    fast code (chosen) and with the literal one (forced)."""
    from pendulab.numerics import crossing

    h = 1e-6
    assert kernel_code(TAYLOR2, -G / length, h) == TAYLOR2_FAST
    searched = _codes_used(monkeypatch, "search_return")
    fast = crossing.search_period(length, alpha, h)
    assert set(searched) == {TAYLOR2_FAST}
    searched.clear()
    monkeypatch.setattr(kernels, "kernel_code", lambda method, c, h: method)
    literal = crossing.search_period(length, alpha, h)
    assert set(searched) == {TAYLOR2}
    assert fast.status == literal.status == Status.FOUND
    e, f = fast.estimate, literal.estimate
    assert e.j == f.j and e.j > 10**5
    assert _same(e.window_theta, f.window_theta) and _same(e.window_omega, f.window_omega)
    assert _same(np.array([e.linear, e.cubic, e.dense]), np.array([f.linear, f.cubic, f.dense]))
