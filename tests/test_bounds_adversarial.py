"""Every stated bound against an adversarial search for its worst case, and the hard cases.

The searches are ``benchmarks/adversarial.py`` with small budgets (``accuracy_claims.claims(quick=True)``,
run once for the module); references there are mpmath at 40-80 digits from the exact
doubles and exact rationals, never the code under test. The last test checks that the
tables of ``docs/accuracy.md`` state the claims, bounds and rows a quick run states.
"""
import math
import re
import sys
from decimal import Decimal
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

import accuracy_claims  # noqa: E402
import adversarial  # noqa: E402

from pendulab.numerics.motion import exact_motion, exact_motion_error_bound  # noqa: E402
from pendulab.numerics.period import FIXED_ITERATIONS_ULPS, fixed_iterations_limit  # noqa: E402
from pendulab.numerics.uncertainty import gravity_estimate, round_significant, significant_digits  # noqa: E402

EPS = 2.0**-52


@pytest.fixture(scope="module")
def quick():
    return accuracy_claims.claims(quick=True)


@pytest.mark.slow
def test_every_search_stays_within_its_bound(quick):
    assert len(quick) == 14
    for row in quick:
        assert row["worst"] <= row["bound"], row


# ---------------------------------------------------------------------------- exact motion
# Roundings of K, omega0 and omega0 t aligned at a zero crossing after 10^4 periods.
HARD_MOTION = (7.456720155578, 30.186002204269425, 3.1409621881538863, 188157.06928849473)


def test_motion_hard_case_is_a_few_ulps():
    length, g, alpha, t = HARD_MOTION
    ex = exact_motion(length, alpha, [t], g)
    theta, omega = adversarial.motion_reference(length, alpha, g, t, dps=80)
    bt, bo = exact_motion_error_bound(length, alpha, [t], g)
    assert abs(ex.theta[0] - theta) <= bt[0]
    assert abs(ex.omega[0] - omega) <= bo[0]
    assert abs(ex.theta[0] - theta) <= 4 * math.ulp(abs(theta))  # a few ulps of theta, not 3.9e-10 rad


@pytest.mark.parametrize("periods", [1e6 + 0.25, 1e9 + 0.75, 2.0**62 + 0.25])
def test_motion_within_bound_after_many_periods(periods):
    """Zero crossings after up to 2^62 periods (the last beyond TwoProduct's range: rationals)."""
    from pendulab.numerics.period import agm_period

    length, alpha = 0.75, math.pi - 1e-9
    t = periods * float(agm_period(length, alpha))
    ex = exact_motion(length, alpha, [t])
    theta, omega = adversarial.motion_reference(length, alpha, adversarial.G, t)
    bt, bo = exact_motion_error_bound(length, alpha, [t])
    assert abs(ex.theta[0] - theta) <= bt[0]
    assert abs(ex.omega[0] - omega) <= bo[0]


def test_motion_scalar_time_keeps_its_shape():
    ex = exact_motion(1.0, 1.0, 0.0)
    assert np.shape(ex.theta) == () and float(ex.theta) == pytest.approx(1.0, abs=4 * EPS)


# ---------------------------------------------------------------------------- T^
def test_t_hat_hard_case_within_the_derived_bound():
    # 6 ulp at l = 1: more than a random sample finds, within the 20 the roundings allow.
    ulps = adversarial.t_hat_ulps(1.0, np.array([3.141592653357749]))[0]
    assert 5 <= ulps <= FIXED_ITERATIONS_ULPS


def test_t_hat_beyond_the_limit_exceeds_the_bound_and_problem5_says_so():
    from pendulab.jobs.problems import problem5

    last = math.nextafter(math.pi, 0)
    assert last > fixed_iterations_limit()
    ulps = adversarial.t_hat_ulps(1.0, np.array([last]))[0]
    assert ulps > FIXED_ITERATIONS_ULPS
    r = problem5(length=1.0, amplitude=last, ns=(10,))
    assert abs(r.t_hat_ulps) == round(ulps) and not r.t_hat_converged
    from pendulab.cli.problems import t_hat_note  # the line the CLI prints for that decision

    assert f"{FIXED_ITERATIONS_ULPS} ulp" in t_hat_note(r)


# ---------------------------------------------------------------------------- significant digits
def test_significant_digits_just_below_a_power_of_ten():
    assert significant_digits(99.99999999999999, 0.4) == 2  # the leading digit is at 10^1
    assert adversarial.digits_rule(99.99999999999999, 0.4) == 2


@pytest.mark.parametrize("value, error", [(99.99999999999999, 0.4), (9.8, 0.05), (98.0, 0.5), (0.009999999999999998, 4e-4)])
def test_the_coursework_program_counts_digits_by_the_same_rule(value, error):
    from pendulab.jobs import coursework

    program = coursework.load()["problem1.py"]
    assert program.significant_digits(value, error) == significant_digits(value, error) == adversarial.digits_rule(value, error)


def test_gravity_text_is_plain_decimal(cli):
    r = gravity_estimate(1.5, 0.3, 2.2, 0.01)
    assert r.significant_digits == 1 and r.g_text == "10"  # g = 12.2, error 2.6 <= 5
    out = cli("gravity", "--length", "1.5", "--length-error", "0.3", "--period", "2.2", "--period-error", "0.01").out
    assert "significant digits guaranteed: 1  (g = 10 m/s^2" in out and "E+" not in out


@pytest.mark.parametrize("value, digits, text", [
    (9.96, 2, "10"), (99.99999999999999, 2, "100"), (999.6, 3, "1000"), (1234.5, 2, "1200"),
    (12.23, 1, "10"), (0.0012345, 3, "0.00123"), (-9.96, 2, "-10"), (9.995, 3, "9.99"),  # 9.995 is 9.99499...
    (1.25e25, 2, "1.3E+25"),
])
def test_round_significant_texts(value, digits, text):
    assert round_significant(value, digits) == text


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(p=st.integers(-20, 20), ulps=st.integers(-3, 3), mant=st.sampled_from([1.0, 5.0, 9.999999999999998, 2.5]),
       q=st.integers(-18, 2), err_ulps=st.integers(-2, 2))
def test_significant_digits_is_the_exact_rule_near_powers_of_ten_and_ties(p, ulps, mant, q, err_ulps):
    value = mant * 10.0**p
    for _ in range(abs(ulps)):
        value = math.nextafter(value, math.copysign(math.inf, ulps))
    error = 0.5 * 10.0 ** (p + q)
    for _ in range(abs(err_ulps)):
        error = math.nextafter(error, math.copysign(math.inf, err_ulps))
    n = significant_digits(value, error)
    assert n == adversarial.digits_rule(value, error)
    if n:  # the text is the exact value rounded to n digits, within half a unit of the n-th
        text = round_significant(value, n)
        assert abs(Decimal(text) - Decimal(value)) <= Decimal(5).scaleb(Decimal(value).adjusted() - n)


# ---------------------------------------------------------------------------- the docs' table
def doc_rows(text):
    body = text.split(accuracy_claims.BEGIN, 1)[1].split(accuracy_claims.END, 1)[0]
    return [[c.strip() for c in line.strip().strip("|").split("|")] for line in body.splitlines()
            if line.startswith("|") and not re.match(r"\|\s*-", line)]


@pytest.mark.slow
def test_docs_table_states_what_a_quick_run_states(quick):
    written = doc_rows((ROOT / "docs" / "accuracy.md").read_text(encoding="utf-8"))
    figures = [accuracy_claims.markdown(*block(True)) for block in accuracy_claims.FIGURES]
    text = accuracy_claims.table(quick, adversarial.t_hat_near_pi(), figures)
    fresh = doc_rows(f"{accuracy_claims.BEGIN}\n{text}\n{accuracy_claims.END}")
    assert len(written) == len(fresh) > 40
    for w, f in zip(written, fresh):
        assert len(w) == len(f)
        if len(f) == 6:  # a claim: where it is stated, the bound and how it is known are the same
            assert w[:3] == f[:3]
        else:  # T^ beyond the limit and the measured figures: the same rows
            assert w[0] == f[0]
