"""Problem 5: rule (11), composite S_n, the singular period integral (1)."""
import math
import tracemalloc

import mpmath
import numpy as np
import pytest
from scipy.integrate import fixed_quad, quad

from pendulab.core.errors import InputError
from pendulab.jobs.problems import problem5
from pendulab.numerics.period import agm_period
from pendulab.numerics.quadrature import (
    GAUSS3,
    Rule,
    composite,
    composite_graded,
    period_integrand,
    period_prefactor,
    quadrature_period,
    substituted_integrand,
)
from reference import G_TEXT, G, period_mp, reference_period

L, ALPHA = 3.5, 4 * math.pi / 5  # problem 5


def s_n_mp(n, dps=40):
    """S_n of rule (11) for the integral in (1), in mpmath at 40 digits, written from (11)."""
    with mpmath.workdps(dps):
        a, b = mpmath.mpf(0), mpmath.mpf(ALPHA)  # the double alpha, as the code integrates
        f = lambda th: 1 / mpmath.sqrt(mpmath.cos(th) - mpmath.cos(b))  # noqa: E731
        h = (b - a) / n
        r = mpmath.sqrt(mpmath.mpf(3) / 5)
        total = 0
        for i in range(n):
            lo, hi = a + i * h, a + (i + 1) * h
            m, mu = (lo + hi) / 2, (hi - lo) / 2
            total += (hi - lo) / 18 * (5 * f(m - r * mu) + 8 * f(m) + 5 * f(m + r * mu))
        return 4 * mpmath.sqrt(mpmath.mpf(L) / (2 * mpmath.mpf(G_TEXT))) * total


def test_rule_11_is_gauss_legendre_3():
    x, w = np.polynomial.legendre.leggauss(3)
    assert np.allclose(GAUSS3.nodes, x, rtol=0, atol=1e-15)
    assert np.allclose(GAUSS3.weights, w, rtol=0, atol=1e-15)
    assert GAUSS3.degree == 5


def test_rule_checks_itself():
    with pytest.raises(InputError, match="sum"):
        Rule("bad weights", (-0.5, 0.5), (1.0, 0.9), 1)
    with pytest.raises(InputError, match="not exact"):
        Rule("claims too much", GAUSS3.nodes, GAUSS3.weights, 6)
    with pytest.raises(InputError, match="more than"):
        Rule("claims too little", GAUSS3.nodes, GAUSS3.weights, 4)


def test_degree_five_exact_and_order_six():
    p = lambda x: 3 * x**5 - x**4 + 2 * x**2 - 7  # noqa: E731
    exact = 3 * 2**6 / 6 - 2**5 / 5 + 2 * 2**3 / 3 - 14  # int_0^2
    assert GAUSS3.apply(p, 0.0, 2.0) == pytest.approx(exact, rel=1e-15)
    errs = [abs(composite(GAUSS3, np.exp, 0.0, 1.0, n) - math.expm1(1.0)) for n in (2, 4, 8)]
    slopes = [math.log2(e0 / e1) for e0, e1 in zip(errs, errs[1:])]
    assert all(5.8 < s < 6.2 for s in slopes), slopes  # smooth integrand: O(h^6)


def test_s1_and_s10_against_mpmath():
    # 5(b) and 5(c): the double-precision sums agree with (11) evaluated at 40 digits.
    for n in (1, 10):
        assert quadrature_period(L, ALPHA, n) == pytest.approx(float(s_n_mp(n)), rel=2e-15)


def test_s_n_against_scipy_gauss_legendre():
    # The same composite sums by scipy's own 3-point Gauss-Legendre (fixed_quad), per subinterval.
    def f(th):
        return 1 / np.sqrt(np.cos(th) - np.cos(ALPHA))

    for n in (1, 10, 100):
        edges = np.linspace(0.0, ALPHA, n + 1)
        total = math.fsum(fixed_quad(f, lo, hi, n=3)[0] for lo, hi in zip(edges, edges[1:]))
        assert quadrature_period(L, ALPHA, n) == pytest.approx(period_prefactor(L, G) * total, rel=1e-14)


def test_singular_rate_is_one_half():
    exact = agm_period(L, ALPHA, iterations=7)
    ns = [10**3, 10**4, 10**5]
    errs = [abs(quadrature_period(L, ALPHA, n) - exact) for n in ns]
    slope = np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert slope == pytest.approx(-0.5, abs=0.01)


def test_integral_against_scipy_quad_alg_weight():
    # (alpha - theta)^(-1/2) is taken by QUADPACK's algebraic weight; the rest is smooth.
    smooth = lambda th: math.sqrt((ALPHA - th) / (math.cos(th) - math.cos(ALPHA))) if th < ALPHA else 1 / math.sqrt(math.sin(ALPHA))  # noqa: E731
    val, _ = quad(smooth, 0.0, ALPHA, weight="alg", wvar=(0.0, -0.5))
    t_quad = period_prefactor(L, G) * val
    assert t_quad == pytest.approx(float(period_mp(L, ALPHA)), rel=1e-12)
    assert t_quad == pytest.approx(agm_period(L, ALPHA, iterations=7), rel=1e-12)
    s = [quadrature_period(L, ALPHA, n) for n in (10, 100, 1000)]
    assert all(x < t_quad for x in s) and s[0] < s[1] < s[2]  # S_n increases towards the integral


def test_substitution_converges_to_rounding_level():
    ref = float(period_mp(L, ALPHA))
    assert quadrature_period(L, ALPHA, 100, substitution=True) == pytest.approx(ref, rel=4e-15)
    with mpmath.workdps(30):  # the substituted integrand at phi = 1: sqrt2 / sqrt(1 - k^2 sin^2 1)
        k = mpmath.sin(mpmath.mpf(ALPHA) / 2)
        v = mpmath.sqrt(2) / mpmath.sqrt(1 - k**2 * mpmath.sin(1) ** 2)
    assert substituted_integrand(ALPHA)(np.array(1.0)) == pytest.approx(float(v), rel=1e-15)


def test_integrand_is_infinite_at_alpha():
    # The reason for 5(a): a closed rule would evaluate this.
    with np.errstate(divide="ignore"):
        assert period_integrand(ALPHA)(np.array(ALPHA)) == np.inf


def test_chunking_does_not_change_the_sum():
    f = period_integrand(ALPHA)
    a = composite(GAUSS3, f, 0.0, ALPHA, 1000)
    b = composite(GAUSS3, f, 0.0, ALPHA, 1000, chunk=7)
    assert a == pytest.approx(b, rel=1e-15)


@pytest.mark.slow
def test_ten_million_subintervals_in_bounded_memory():
    tracemalloc.start()
    try:
        t = quadrature_period(L, ALPHA, 10**7)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 50 * 2**20  # measured: about 9 MB
    exact = agm_period(L, ALPHA, iterations=7)
    assert abs(t - exact) == pytest.approx(abs(quadrature_period(L, ALPHA, 10**5) - exact) / 10, rel=1e-3)


def test_problem5_table():
    r = problem5()
    exact = agm_period(L, ALPHA, iterations=7)
    assert r.t_hat == exact
    assert [row.n for row in r.rows] == [1, 10, 100, 1000, 10000, 100000]
    for row in r.rows:
        assert row.error == abs(row.estimate - exact)
        assert row.substitution_error < 1e-6 or row.n == 1
    assert [round(row.rate, 2) for row in r.rows[1:]] == [0.5] * 5
    assert r.single == r.rows[0].estimate and r.composite10 == r.rows[1].estimate
    from pendulab.report.words import sentence  # 5(a) in the words the CLI prints

    assert "infinite" in sentence("p5.answer_5a")


@pytest.mark.parametrize("n", [0, -1, 1.5, "10"])
def test_bad_n(n):
    with pytest.raises(InputError) as exc:
        quadrature_period(L, ALPHA, n)
    assert exc.value.name == "n"


@pytest.mark.parametrize("n", [10**7 + 1, 10**9])
def test_n_beyond_the_cap_is_refused_before_any_work(n):
    # 1e9 panels were accepted: minutes of work for half a digit more than 1e7 gives.
    with pytest.raises(InputError) as exc:
        quadrature_period(L, ALPHA, n)
    assert exc.value.name == "n" and "[1, 10000000]" in str(exc.value)
    with pytest.raises(InputError):
        composite(GAUSS3, np.exp, 0.0, 1.0, n)
    with pytest.raises(InputError):
        composite_graded(GAUSS3, np.exp, 1.0, 1e-3, n)


def test_a_table_of_more_than_2e7_panels_in_all_is_refused():
    from pendulab.numerics.quadrature import convergence_table

    with pytest.raises(InputError, match=r"summing to at most 2e\+07 \(these sum to 3e\+07\)"):
        convergence_table(L, ALPHA, [10**7] * 3, 6.2)


def test_the_cap_is_past_the_point_of_use():
    """At the cap, the substituted rule is long at the rounding level (mpmath's elliptic K as
    reference), and the plain rule still loses its half digit per decade of n: n^(-1/2)."""
    exact = float(4 * mpmath.sqrt(mpmath.mpf(L) / G) * mpmath.ellipk(mpmath.sin(mpmath.mpf(ALPHA) / 2) ** 2))
    assert abs(quadrature_period(L, ALPHA, 100, substitution=True) - exact) < 4 * 2.0**-52 * exact
    e3, e4 = (abs(quadrature_period(L, ALPHA, n) - exact) for n in (1000, 10000))
    assert math.log10(e3 / e4) == pytest.approx(0.5, abs=1e-3)


def test_bad_amplitude_and_interval():
    with pytest.raises(InputError):
        quadrature_period(L, math.pi, 10)
    with pytest.raises(InputError):
        composite(GAUSS3, np.exp, 1.0, 0.0, 10)


def test_convergence_plot_draws_the_table():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from pendulab.plots.problems import quadrature_convergence

    r = problem5(ns=(10, 100, 1000))
    fig, ax = plt.subplots()
    try:
        assert quadrature_convergence(r, ax) is ax
        lines = ax.lines
        assert len(lines) == 3  # S_n, the slope guide, the substitution
        assert list(lines[0].get_ydata()) == [row.error for row in r.rows]
    finally:
        plt.close(fig)


@pytest.mark.parametrize("alpha", [ALPHA, math.pi - 1e-15])
def test_substituted_errors_are_measured_against_the_stated_reference(alpha):
    # T^ (7 iterations) has converged at the example, not within 1e-15 of pi; the table's
    # substituted errors and the stated reference must name the same period.
    r = problem5(L, alpha, ns=(10, 100))
    with mpmath.workdps(50):  # (8) to convergence, in mpmath, g the double G as the code takes it
        a = mpmath.mpf(alpha)
        true = float(2 * mpmath.pi * mpmath.sqrt(mpmath.mpf(L) / mpmath.mpf(G)) / mpmath.agm(1, mpmath.cos(a / 2)))
    assert r.substitution_reference == (r.t_hat if r.t_hat_converged else r.period)
    assert (r.substitution_reference == r.t_hat) == (alpha == ALPHA)
    for row in r.rows:
        assert row.substitution_error == abs(row.substitution_estimate - r.substitution_reference)
    assert abs(r.period - true) <= math.ulp(true) / 2


# ------------------------------------------------------------------ the edges: tiny amplitudes, near pi
def s_n_sin_form_mp(alpha: float, n: int, length: float = 1.0, dps: int = 50):
    """S_n of rule (11) on [0, alpha] with the integrand 1/sqrt(2 sin((a+t)/2) sin((a-t)/2)),
    in mpmath (unbounded exponent range: no underflow at alpha = 1e-300), nodes exact."""
    with mpmath.workdps(dps):
        a = mpmath.mpf(alpha)
        f = lambda th: 1 / mpmath.sqrt(2 * mpmath.sin((a + th) / 2) * mpmath.sin((a - th) / 2))  # noqa: E731
        h = a / n
        r = mpmath.sqrt(mpmath.mpf(3) / 5)
        total = 0
        for i in range(n):
            m, mu = (i + mpmath.mpf(1) / 2) * h, h / 2
            total += mu / 9 * (5 * f(m - r * mu) + 8 * f(m) + 5 * f(m + r * mu))
        return 4 * mpmath.sqrt(mpmath.mpf(length) / (2 * mpmath.mpf(G_TEXT))) * total


@pytest.mark.parametrize("alpha", [1e-160, 1e-200, 1e-300, 5e-324, 1e-3, ALPHA, math.pi - 1e-12])
@pytest.mark.parametrize("n", [1, 10, 100])
def test_singular_sum_at_every_amplitude_against_mpmath(alpha, n):
    # The form 2 sin sin underflows there (inf at 1e-200, 1.93320 for 1.93527 at 1e-160).
    assert quadrature_period(1.0, alpha, n) == pytest.approx(float(s_n_sin_form_mp(alpha, n)), rel=4e-15)


@pytest.mark.slow
def test_singular_sum_nodes_keep_their_distance_to_alpha():
    # With 10^4 panels the last node lies alpha/(9 10^4) from the singularity; the node as
    # alpha - theta would cost 2e-13; the reflected variable keeps S_n to rounding.
    assert quadrature_period(L, ALPHA, 10**4) == pytest.approx(float(s_n_mp(10**4, dps=25)), rel=2e-15)


def test_substituted_integrand_keeps_k_prime_near_pi():
    for gap in (1e-9, 1e-12, 1e-15):
        alpha = math.pi - gap
        with mpmath.workdps(40):
            kp = mpmath.cos(mpmath.mpf(alpha) / 2)  # k' of the double alpha, exactly
            k = mpmath.sin(mpmath.mpf(alpha) / 2)
            at_peak = mpmath.sqrt(2) / kp
            at_half = mpmath.sqrt(2) / mpmath.sqrt(1 - k**2 * mpmath.sin(mpmath.mpf(0.5)) ** 2)
        f = substituted_integrand(alpha)
        g = substituted_integrand(alpha, reflected=True)
        assert g(np.array(0.0)) == pytest.approx(float(at_peak), rel=2e-16)
        assert f(np.array(0.5)) == pytest.approx(float(at_half), rel=4e-16)


@pytest.mark.parametrize("gap", [1e-1, 1e-6, 1e-9, 1e-12, 1e-15, 3.2e-16])
def test_graded_panels_reach_rounding_level_up_to_pi(gap):

    alpha = math.pi - gap  # 3.2e-16: the double rounds to pi - 3.2e-16 (k' = 1.6e-16)
    ref = float(reference_period(1.0, alpha))
    assert quadrature_period(1.0, alpha, 3000, substitution=True, graded=True) == pytest.approx(ref, rel=4e-15)


def test_equal_panels_converge_once_they_resolve_the_peak():

    # The worst case: k rounds to 1 at pi - 1e-9; the k' form gives the true 29.126 with grading
    # and the equal panels move towards it instead of settling on 26.168.
    alpha = math.pi - 1e-3  # k' = 5e-4: n = 5/k' = 1e4 panels give 1e-12
    ref = float(reference_period(1.0, alpha))
    errs = [abs(quadrature_period(1.0, alpha, n, substitution=True) / ref - 1) for n in (10**3, 10**4)]
    assert errs[0] > 1e-5 and errs[1] < 1e-11
    near = math.pi - 1e-9
    assert quadrature_period(1.0, near, 1000, substitution=True, graded=True) == pytest.approx(
        float(reference_period(1.0, near)), rel=1e-12)


def test_composite_graded_on_a_peak_of_known_integral():
    from pendulab.numerics.quadrature import composite_graded

    for eps in (1e-3, 1e-9, 1e-15):
        f = lambda x, e=eps: 1 / np.sqrt(e * e + x * x)  # noqa: E731
        exact = math.asinh(1 / eps)  # int_0^1 dx / sqrt(eps^2 + x^2)
        assert composite_graded(GAUSS3, f, 1.0, eps / 32, 3000) == pytest.approx(exact, rel=4e-15)
    assert composite_graded(GAUSS3, np.exp, 1.0, 1e-3, 1000) == pytest.approx(math.expm1(1.0), rel=4e-16)


def test_graded_needs_the_substitution():
    with pytest.raises(InputError, match="graded"):
        quadrature_period(L, ALPHA, 10, graded=True)


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=60, deadline=None)
@given(alpha=st.floats(5e-324, 1e-9), n=st.sampled_from([1, 10, 100]))
def test_tiny_amplitudes_give_the_small_amplitude_sum(alpha, n):
    # For alpha < 1e-9, sinc(alpha y/2) is 1 to rounding: S_n no longer depends on alpha,
    # down to the smallest subnormal (the form 2 sin sin is inf below about 1e-154).
    assert quadrature_period(1.0, alpha, n) == pytest.approx(quadrature_period(1.0, 1e-9, n), rel=4e-16)
