"""Newton's divided differences and the inverse cubic, against scipy and a known function."""
import numpy as np
import pytest
from scipy.interpolate import BarycentricInterpolator

from pendulab.interpolation import divided_differences, inverse_cubic, newton_eval


def test_newton_form_agrees_with_scipy_barycentric():
    rng = np.random.default_rng(1)
    x = np.sort(rng.uniform(-1, 1, 6))
    y = rng.normal(size=6)
    coef = divided_differences(x, y)
    xs = np.linspace(-1, 1, 17)
    assert np.allclose(newton_eval(coef, x, xs), BarycentricInterpolator(x, y)(xs), atol=1e-10)
    assert np.allclose(newton_eval(coef, x, x), y, atol=1e-12)


def test_leading_coefficient_is_the_polynomial_leading_coefficient():
    x = np.array([0.0, 1.0, 3.0, 4.0])
    y = 2 * x**3 - x + 5
    assert divided_differences(x, y)[-1] == pytest.approx(2.0)


def test_inverse_cubic_estimates_its_own_error():
    # t(z) = arcsin(z): the zero is t = 0; nodes straddle it like z2 in problem 3(d).
    z = np.array([0.35, 0.12, -0.08, -0.31])
    t = np.arcsin(z) + 5.0
    fifth = (0.5, np.arcsin(0.5) + 5.0)
    res = inverse_cubic(z, t, fifth)
    true_error = 5.0 - res.value
    assert abs(true_error) < 1e-3
    # The estimate has the right order of magnitude (it is an estimate, not a bound).
    assert 0.1 < abs(res.error_estimate / true_error) < 10


def test_repeated_nodes_are_rejected():
    with pytest.raises(ValueError):
        divided_differences([0.0, 0.0, 1.0], [1.0, 2.0, 3.0])
