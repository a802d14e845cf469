"""Problem 4: least squares by the normal equations, basis (10)."""
import math
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
import scipy.linalg
from hypothesis import given
from hypothesis import strategies as st

from pendulab.core.errors import InputError, NumericalError
from pendulab.jobs.problems import problem4
from pendulab.numerics.lsq import least_squares, round_half_up
from pendulab.numerics.period import agm_period
from pendulab.numerics.simulation import simulate


def basis10_python(t):
    """Basis (10) written out with math, independently of lsq.TRIG_BASIS."""
    return [1.0, math.sin(t), math.cos(t), math.sin(2 * t), math.cos(2 * t), math.sin(3 * t), math.cos(3 * t)]


@pytest.fixture(scope="module")
def p4():
    return problem4()


def test_round_half_up_on_exact_values():
    assert round_half_up([0.5, -0.5, 2.5, -2.5, 1.5], 0).tolist() == [1.0, -1.0, 3.0, -3.0, 2.0]  # not half-even
    assert round_half_up(0.125, 2) == 0.13 and round_half_up(-0.125, 2) == -0.13  # exact binary ties
    # 1.0000015 as a double lies below the tie: its exact value decides (round(x * 1e6) gives 1.000002).
    assert Fraction(1.0000015) < Fraction("1.0000015")
    assert round_half_up(1.0000015, 6) == 1.000001
    assert round_half_up(2.0000015, 6) == float(Decimal.from_float(2.0000015).quantize(Decimal("1e-6"), rounding="ROUND_HALF_UP"))
    for bad in (-1, 16, 1.5, "6"):
        with pytest.raises(InputError):
            round_half_up(1.0, bad)


@given(st.floats(allow_nan=True, allow_infinity=True), st.integers(0, 15))
def test_round_half_up_takes_every_double(x, decimals):
    """Every double, the largest and the non-finite included, rounds as exact rationals say:
    the nearest multiple of 10^-decimals to its exact value, ties away from zero."""
    got = float(round_half_up(x, decimals))
    if not math.isfinite(x):
        assert got == x or (math.isnan(got) and math.isnan(x))
        return
    q = Fraction(1, 10**decimals)
    f = abs(Fraction(x)) / q
    n = math.floor(f) + (1 if f - math.floor(f) >= Fraction(1, 2) else 0)
    assert got == math.copysign(float(n * q), x)


def test_data_follow_the_formulas(p4):
    # T from (8) with 7 iterations, t_max = ceil(T) = 4, h = 0.01: 401 points (not Y_0..Y_600).
    assert p4.t_hat == agm_period(3.5, math.pi / 4, iterations=7)
    assert p4.t_max == 4.0 and p4.points == 401
    assert p4.last_points.shape == (10, 2)
    assert p4.last_points[:, 0] == pytest.approx(np.arange(391, 401) / 100, abs=1e-12)
    tr = simulate(3.5, math.pi / 4, 0.01, 4.0)
    assert np.array_equal(p4.last_points[:, 1], tr.theta[-10:])


def test_normal_equations_against_python_sums(p4):
    t, y = p4.data.t, p4.data.theta
    rows = [basis10_python(tj) for tj in t.tolist()]
    a = [[math.fsum(r[i] * r[k] for r in rows) for k in range(7)] for i in range(7)]
    b = [math.fsum(r[i] * yj for r, yj in zip(rows, y.tolist())) for i in range(7)]
    q = Decimal("1e-6")
    a6 = [[float(Decimal(x).quantize(q, rounding="ROUND_HALF_UP")) for x in row] for row in a]
    b6 = [float(Decimal(x).quantize(q, rounding="ROUND_HALF_UP")) for x in b]
    assert p4.fit.normal_matrix.tolist() == a6
    assert p4.fit.normal_rhs.tolist() == b6
    assert p4.fit.normal_matrix[0, 0] == 401.0
    assert np.allclose(p4.fit.normal_matrix_unrounded, a, rtol=0, atol=1e-11)


def test_positive_definite(p4):
    a = p4.fit.normal_matrix
    d = p4.fit.definiteness
    assert d.symmetric and d.cholesky and d.positive_definite
    scipy.linalg.cholesky(a, lower=True)  # raises LinAlgError if not positive definite
    eig = scipy.linalg.eigh(a, eigvals_only=True)
    assert d.min_eigenvalue == pytest.approx(eig[0], rel=1e-10) and eig[0] > 1
    assert d.condition_number == pytest.approx(np.linalg.cond(a), rel=1e-8)
    # Weyl: rounding moved lambda_min by less than lambda_min itself.
    assert d.rounding_perturbation <= 7 * 5e-7 + 1e-12 < d.min_eigenvalue


def test_coefficients_against_lstsq(p4):
    t, y = p4.data.t, p4.data.theta
    phi = np.array([basis10_python(tj) for tj in t.tolist()])
    ref, *_ = np.linalg.lstsq(phi, y, rcond=None)
    # Unrounded normal equations agree with lstsq to (cond^2) rounding.
    exact = least_squares(t, y)
    assert np.max(np.abs(exact.coefficients - ref)) < 1e-11
    # The rounding to 6 decimals moves them by at most ||A^-1|| (||dA|| ||c|| + ||dr||).
    fit = p4.fit
    shift = np.max(np.abs(fit.coefficients - ref))
    da = np.linalg.norm(fit.normal_matrix - fit.normal_matrix_unrounded, 2)
    dr = np.linalg.norm(fit.normal_rhs - fit.normal_rhs_unrounded)
    bound = (da * np.linalg.norm(ref) + dr) / np.linalg.eigvalsh(fit.normal_matrix)[0]
    assert shift <= bound
    assert fit.coefficient_shift == pytest.approx(shift, rel=1e-6)
    assert 1e-9 < shift < 1e-6  # measured: 1.4e-7
    assert list(fit.coefficient_dict()) == ["gamma", "a0", "b0", "a1", "b1", "a2", "b2"]


def test_deviations_and_answer(p4):
    t, y = p4.data.t, p4.data.theta
    phi = np.array([basis10_python(tj) for tj in t.tolist()])
    ref, *_ = np.linalg.lstsq(phi, y, rcond=None)
    res = y - phi @ ref
    ssd_ref = math.fsum(res**2)
    assert ssd_ref * (1 - 1e-12) <= p4.fit.ssd <= ssd_ref * (1 + 1e-3)  # lstsq's SSD is the minimum
    assert p4.fit.max_deviation == pytest.approx(np.max(np.abs(res)), rel=1e-3)
    assert p4.fit.max_deviation > 1e-5 and not p4.below_tolerance  # 4(d)(ii): no
    from pendulab.report.words import sentence  # the words the CLI prints for that decision

    assert sentence("p4.answer.no", deviation=p4.fit.max_deviation, at=p4.fit.argmax_deviation,
                    tolerance=p4.tolerance, exact=p4.exact_deviation).startswith("No")
    assert p4.exact_deviation > 1e-5


def test_t_max_override_gives_the_originals_601_points():
    r = problem4(t_max=6.0)
    assert r.points == 601 and r.t_max_rule == "given"


def test_exact_fit_and_a_generic_basis():
    t = np.linspace(0, 4, 401)
    y = 1 + 2 * np.sin(t) - 3 * np.cos(3 * t)
    fit = least_squares(t, y)
    assert fit.coefficients == pytest.approx([1, 2, 0, 0, 0, 0, -3], abs=1e-12)
    assert fit.ssd < 1e-24
    y2 = 0.5 - t + 0.25 * t**2 + np.sin(7 * t) * 1e-3
    poly = least_squares(t, y2, [lambda s: np.ones_like(s), lambda s: s, lambda s: s**2])
    assert poly.names == ("c0", "c1", "c2")
    assert poly.coefficients == pytest.approx(np.polyfit(t, y2, 2)[::-1], abs=1e-12)


def test_dependent_basis_and_bad_data():
    t = np.linspace(0, 1, 11)
    with pytest.raises(NumericalError, match="positive definite"):
        least_squares(t, t, [lambda s: np.ones_like(s), lambda s: 2 * np.ones_like(s)])
    with pytest.raises(InputError):
        least_squares(t, t[:-1])
    with pytest.raises(InputError):
        least_squares(t[:3], t[:3])  # 3 points, 7 functions
    with pytest.raises(InputError):
        least_squares(t, np.full_like(t, np.nan))
