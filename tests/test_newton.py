"""Problem 2: Newton's method on (9), q_k, k_max, the convergence interval."""
import math

import mpmath
import numpy as np
import pytest
from scipy.optimize import brentq

from pendulab.core.errors import InputError, NumericalError
from pendulab.jobs.problems import problem2
from pendulab.numerics.newton import PeriodEquation, check_interval, newton
from reference import G_TEXT, G


def f_ref(alpha, length=0.5, target=1.5):
    """(9) minus the target, written out independently of the code under test."""
    return 2 * math.pi / math.sqrt(G / length) * (1 + math.sin(alpha / 2) ** 2 / 4) - target


def root_mp(length="0.5", target="1.5", dps=50):
    """The root of (9) = target by mpmath.findroot at 50 digits."""
    with mpmath.workdps(dps):
        p = mpmath.sqrt(mpmath.mpf(G_TEXT) / mpmath.mpf(length))
        f = lambda a: 2 * mpmath.pi / p * (1 + mpmath.sin(a / 2) ** 2 / 4) - mpmath.mpf(target)  # noqa: E731
        return mpmath.findroot(f, 1.0)


def test_root_against_brentq_and_mpmath():
    r = problem2()
    z_brent = brentq(f_ref, 0.1, 3.0, xtol=1e-16, rtol=4 * np.finfo(float).eps)
    z_mp = root_mp()
    assert r.alpha == pytest.approx(z_brent, abs=4e-15)
    assert abs(r.alpha - float(z_mp)) <= r.run.error_estimate  # the estimate bounds the true error
    assert abs(r.alpha - float(z_mp)) < 4e-15
    assert r.alpha_deg == pytest.approx(float(mpmath.degrees(z_mp)), abs=1e-12)
    assert r.alpha_deg == pytest.approx(57.1921010531797, abs=1e-12)  # degrees(mpmath root)
    assert r.closed_form == pytest.approx(float(z_mp), abs=1e-14)


def test_interval_conditions_hold_with_their_numbers():
    r = problem2()
    chk = r.interval
    assert chk.holds and len(chk.conditions) == 5
    assert r.interval_deg == (55.0, 60.0)
    assert chk.a < float(root_mp()) < chk.b
    # Sign change, checked with the independent f.
    assert f_ref(chk.a) < 0 < f_ref(chk.b)
    assert chk.conditions[0].values["f_a"] == pytest.approx(f_ref(chk.a), abs=1e-15)
    # Newton steps from the ends, by hand.
    a_p = 2 * math.pi / math.sqrt(G / 0.5)
    step_a = abs(f_ref(chk.a) / (a_p * math.sin(chk.a) / 8))
    assert chk.conditions[3].values["step"] == pytest.approx(step_a, rel=1e-12)
    assert step_a <= chk.b - chk.a
    assert r.x0 == chk.b  # f(b) f''(b) > 0: Fourier's end


def test_every_start_in_the_interval_converges():
    eq = PeriodEquation(0.5, 1.5)
    chk = eq.interval()
    z = float(root_mp())
    for x0 in np.linspace(chk.a, chk.b, 41):
        assert eq.newton(float(x0)).root == pytest.approx(z, abs=4e-15)


def test_a_failing_interval_is_reported():
    eq = PeriodEquation(0.5, 1.5)
    chk = eq.check(math.radians(30), math.radians(60))
    assert not chk.holds
    failed = [c.name for c in chk.conditions if not c.holds]
    assert failed == ["step_from_a"]  # from 30 deg the step overshoots b


def test_quotients_approach_the_asymptotic_constant():
    r = problem2()
    run = r.run
    z = root_mp()
    with mpmath.workdps(30):  # |f''/(2 f')| = |cot(z)|/2 for (9)
        c_ref = float(abs(mpmath.cot(z)) / 2)
    assert run.asymptotic_constant == pytest.approx(c_ref, rel=1e-12)
    assert run.k_max is not None
    assert abs(run.q_kmax - c_ref) / c_ref < 0.01
    # k_max is the last quotient free of rounding: the next one is not.
    assert run.q_rounding[run.k_max] <= 0.01
    if run.k_max + 1 < len(run.q_rounding):
        assert run.q_rounding[run.k_max + 1] > 0.01
    # Superlinear: successive correction ratios go to 0.
    good = [x for x in r.ratios[: run.k_max + 2] if x is not None]
    assert all(b < a for a, b in zip(good, good[1:])) and good[-1] < 1e-6


def test_generic_newton_sqrt2():
    run = newton(lambda x: x * x - 2, lambda x: 2 * x, 2.0, d2f=lambda x: 2.0, f_scale=4.0)
    assert run.root == pytest.approx(math.sqrt(2), abs=4.5e-16)
    c = 1 / (2 * math.sqrt(2))  # |f''/(2f')| at sqrt(2)
    assert run.asymptotic_constant == pytest.approx(c, rel=1e-14)
    assert abs(run.q_kmax - c) / c < 0.01
    assert run.iterates[0] == 2.0 and len(run.corrections) == run.iterations


def test_generic_newton_failures():
    with pytest.raises(NumericalError, match="did not converge"):
        newton(lambda x: x * x + 1, lambda x: 2 * x, 0.5, max_iter=30)
    with pytest.raises(NumericalError, match="f'"):
        newton(lambda x: x * x - 1, lambda x: 2 * x, 0.0)
    with pytest.raises(NumericalError, match="left the domain"):
        PeriodEquation(0.5, 1.5).newton(1e-3)  # f' ~ alpha/8 tiny: the first step leaves (0, pi)


def test_check_interval_rejects_reversed_ends():
    with pytest.raises(InputError):
        check_interval(math.sin, math.cos, lambda x: -math.sin(x), 2.0, 1.0)


@pytest.mark.parametrize("x0", [0.0, -1.0, math.pi, 4.0, math.nan])
def test_start_outside_the_domain(x0):
    with pytest.raises(InputError) as exc:
        problem2(x0=x0)
    assert exc.value.name == "x0"


@pytest.mark.parametrize("target", [1.0, 2 * math.pi / math.sqrt(G / 0.5), 1.25 * 2 * math.pi / math.sqrt(G / 0.5), 2.0])
def test_unreachable_target(target):
    with pytest.raises(InputError) as exc:
        problem2(target=target)
    assert exc.value.name == "target"


def test_other_targets_and_lengths_match_brentq():
    for length, target in [(0.5, 1.45), (0.5, 1.7), (2.0, 3.0), (1.0, 2.4)]:
        r = problem2(length, target)
        assert r.interval.holds
        z = brentq(f_ref, 1e-9, math.pi - 1e-9, args=(length, target), xtol=1e-16)
        assert r.alpha == pytest.approx(z, abs=1e-13)


def test_newton_plot_draws_the_corrections():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from pendulab.plots.problems import newton_corrections

    r = problem2()
    fig, ax = plt.subplots()
    try:
        assert newton_corrections(r, ax) is ax
        line = ax.lines[0]
        assert list(line.get_ydata()) == [abs(d) for d in r.run.corrections if d != 0]
    finally:
        plt.close(fig)


def test_results_carry_codes_and_their_numbers():
    # A given tolerance: the run stops on the first correction at or below it.
    run = newton(lambda x: x * x - 2, lambda x: 2 * x, 1.0, tol=1e-10)
    assert (run.criterion, run.tol, run.stop_reason) == ("tolerance", 1e-10, "small_correction")
    assert run.stop_limit == 1e-10 and run.stop_correction == abs(run.corrections[-1]) <= 1e-10
    assert all(abs(c) > 1e-10 for c in run.corrections[:-1])
    # The default: the rounding level of x.
    run = newton(lambda x: x * x - 2, lambda x: 2 * x, 1.0)
    assert (run.criterion, run.tol, run.stop_reason) == ("rounding_level", None, "small_correction")
    assert run.stop_correction == abs(run.corrections[-1]) <= run.stop_limit
    # A start on the root: f(x_0) = 0 exactly, no correction to report.
    run = newton(lambda x: x - 2, lambda x: 1.0, 2.0)
    assert (run.stop_reason, run.stop_correction, run.stop_limit, run.iterations) == ("zero_value", None, None, 0)


def test_every_code_has_its_words_in_both_catalogues():
    import typing

    from pendulab.jobs.problems import TMaxRule
    from pendulab.numerics import newton as nt
    from pendulab.report.words import sentence

    numbers = {"tol": 1e-3, "correction": 1e-9, "limit": 2e-9, "f_a": -1.0, "f_b": 1.0, "min": 0.1, "max": 0.2,
               "step": 0.01, "width": 0.1, "relation": "<=", "t_hat": 3.9}
    keys = ([f"p2.criterion.{c}" for c in typing.get_args(nt.Criterion)]
            + [f"p2.stop.{c}" for c in typing.get_args(nt.StopReason)]
            + [f"p2.condition.{c}" for c in typing.get_args(nt.ConditionName)]
            + [f"p4.t_max.{c}" for c in typing.get_args(TMaxRule)]
            + ["p1.rule", "p1.abs_error_formula", "p1.rel_error_formula"])
    for lang in ("en", "pt"):
        for key in keys:
            assert sentence(key, lang, **numbers).strip(), (lang, key)
    # check_interval names exactly the conditions the catalogue has words for.
    chk = PeriodEquation(0.5, 1.5).interval()
    assert [c.name for c in chk.conditions] == list(typing.get_args(nt.ConditionName))
