"""Polynomial interpolation in Newton's form, and the inverse interpolation of problem 3(d).

The period is the time at which ``theta'`` vanishes: interpolating the table
``(z2_j, t_j)`` (inverse interpolation) by a cubic ``p`` gives ``T ~ p(0)``.

References
----------
.. [1] R. L. Burden, J. D. Faires, *Numerical Analysis*, 9th ed., sections 3.1 (error
   formula, Theorem 3.3) and 3.3 (divided differences, Newton's form).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.errors import InputError
from .results import Result


def divided_differences(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Newton coefficients ``f[x0], f[x0,x1], ..., f[x0..xn]`` of the table ``(x, y)``.

    The standard in-place table (Burden-Faires, Algorithm 3.2); ``x`` must be distinct.
    """
    x = np.asarray(x, dtype=float)
    coef = np.array(y, dtype=float)
    if len(np.unique(x)) != len(x):
        raise InputError("x", x.tolist(), "distinct interpolation nodes")
    for k in range(1, len(x)):
        coef[k:] = (coef[k:] - coef[k - 1 : -1]) / (x[k:] - x[: len(x) - k])
    return coef


def newton_eval(coef: np.ndarray, x_nodes: np.ndarray, x: float | np.ndarray) -> float | np.ndarray:
    """Evaluate ``p(x) = c0 + c1 (x - x0) + ... + cn (x - x0)...(x - x_{n-1})`` by Horner's rule."""
    p = np.full_like(np.asarray(x, dtype=float), coef[-1])
    for c, xn in zip(coef[-2::-1], x_nodes[len(coef) - 2 :: -1]):
        p = p * (x - xn) + c
    return p if np.ndim(p) else float(p)


@dataclass(frozen=True, eq=False)
class InverseInterpolation(Result):
    """``p`` interpolating ``(z2_j, t_j)``, ``j = 0..3``, its value ``p(0)`` and error estimate.

    Attributes
    ----------
    z2, t : ndarray, shape (4,)
        The table of problem 3(d): ``z2`` changes sign among the nodes.
    coefficients : ndarray, shape (4,)
        Newton's divided differences ``t[z2_0], ..., t[z2_0..z2_3]`` (``inf`` where they
        exceed the doubles, as for amplitudes below about 1e-100; ``value`` and
        ``error_estimate`` are computed on scaled nodes and stay finite).
    value : float
        ``p(0)``, the estimate of the time at which ``theta' = 0``.
    fifth : tuple of float
        The extra node ``(z2_4, t_4)`` used for the error estimate.
    fourth_difference : float
        ``t[z2_0, .., z2_4]``, which approximates ``f^(4)(xi)/4!`` (spec footnote 5).
    error_estimate : float
        ``t[z2_0..z2_4] * prod_j (0 - z2_j)``: the interpolation error formula with the
        unknown derivative replaced by the 5-node divided difference.
    rounding_level : float
        How far rounding the five times ``t_k`` to doubles (half an ulp each) can move
        ``error_estimate``: ``sum_k ulp(t_k)/2 |prod_j z2_j| / |prod_(i != k) (z2_k - z2_i)|``.
        An estimate at or below it is rounding noise, not interpolation error
        (:attr:`error_estimate_resolved`).
    """

    z2: np.ndarray
    t: np.ndarray
    coefficients: np.ndarray
    value: float
    fifth: tuple[float, float]
    fourth_difference: float
    error_estimate: float
    rounding_level: float = 0.0

    @property
    def error_estimate_resolved(self) -> bool:
        """Whether the error estimate stands above the rounding of the times ``t_k``."""
        return abs(self.error_estimate) > self.rounding_level


def linear_zero(t_j, h, z2_j, z2_j1):
    """The zero of the line through ``(t_j, z2_j)`` and ``(t_j + h, z2_j1)``: the linear
    estimate of problem 3(c). Scalars or arrays (one pendulum per element)."""
    return t_j + h * z2_j / (z2_j - z2_j1)


def inverse_cubic_rows(z2: np.ndarray, t: np.ndarray, fifth_z2: np.ndarray, fifth_t: np.ndarray):
    """``p(0)`` and the error estimate of :func:`inverse_cubic` for each row of a table.

    ``z2, t`` have shape ``(m, 4)``, ``fifth_z2, fifth_t`` shape ``(m,)``. Each row's nodes are
    scaled by the power of two nearest above their largest ``|z2|`` (see
    :func:`inverse_cubic`), and Newton's divided differences are the in-place table of
    Burden-Faires, Algorithm 3.2, on the five nodes at once; its first four coefficients
    are those of the cubic on the first four nodes. Nothing is checked: a row with repeated
    or zero nodes gives ``inf`` or NaN (the sweep masks the pendulums not found).

    Returns
    -------
    value, error_estimate : ndarray, shape (m,)
    coef : ndarray, shape (m, 5)
        The divided differences of the scaled five-node table.
    x5 : ndarray, shape (m, 5)
        The scaled nodes.
    exponent : ndarray of int, shape (m,)
        ``e`` with the nodes scaled by ``2^-e``.
    """
    x5 = np.concatenate([np.asarray(z2, dtype=float), np.asarray(fifth_z2, dtype=float)[:, None]], axis=1)
    exponent = np.frexp(np.max(np.abs(x5), axis=1))[1]
    x5 = np.ldexp(x5, -exponent[:, None])
    coef = np.concatenate([np.asarray(t, dtype=float), np.asarray(fifth_t, dtype=float)[:, None]], axis=1)
    for k in range(1, 5):
        coef[:, k:] = (coef[:, k:] - coef[:, k - 1 : -1]) / (x5[:, k:] - x5[:, : 5 - k])
    p = coef[:, 3].copy()
    for k in (2, 1, 0):  # Horner's rule at 0 on the first four nodes
        p = p * (0.0 - x5[:, k]) + coef[:, k]
    error = coef[:, 4] * np.prod(0.0 - x5[:, :4], axis=1)
    return p, error, coef, x5, exponent


def inverse_cubic(z2: np.ndarray, t: np.ndarray, fifth: tuple[float, float]) -> InverseInterpolation:
    """Inverse cubic interpolation ``T ~ p(0)`` through four points, problem 3(d).

    Parameters
    ----------
    z2, t : array_like, shape (4,)
        ``theta'`` values (distinct) and their times.
    fifth : (float, float)
        A fifth point ``(z2, t)`` of the same simulation, for the error estimate:
        ``e(0) = f^(4)(xi)/4! * prod(0 - z2_j) ~ f[z2_0, .., z2_4] * prod(0 - z2_j)``.

    Notes
    -----
    The nodes are scaled by the power of two ``s`` nearest above ``max |z2|``: the
    divided differences of ``(z2/s, t)`` are those of ``(z2, t)`` times ``s^k``, exactly
    (a power of two), and ``p(0)`` and the error estimate are unchanged bit for bit. Unscaled,
    ``t[z2_0..z2_4] ~ h/z2^4`` overflows once ``z2 ~ alpha`` is below about 1e-77
    (``p(0)`` became ``-inf`` at ``alpha = 1e-160``).
    """
    z2 = np.asarray(z2, dtype=float)
    t = np.asarray(t, dtype=float)
    x5 = np.append(z2, fifth[0])
    t5 = np.append(t, fifth[1])
    big = float(np.max(np.abs(x5)))
    if not (math.isfinite(big) and big > 0):
        raise InputError("z2", x5.tolist(), "finite interpolation nodes, not all zero")
    if len(np.unique(x5)) != len(x5):
        raise InputError("z2", x5.tolist(), "distinct interpolation nodes")
    values, errors, five2, x52, exps = inverse_cubic_rows(z2[None, :], t[None, :], x5[None, 4], t5[None, 4])
    value, error, five, x5, e = float(values[0]), float(errors[0]), five2[0], x52[0], int(exps[0])
    coef = five[:4]
    x = x5[:4]
    prod = float(np.prod(0.0 - x))
    # Weights of the fourth divided difference, 1/prod_(i != k)(x_k - x_i) (Burden-Faires (3.10)).
    weights = [1.0 / float(np.prod([x5[k] - x5[i] for i in range(5) if i != k])) for k in range(5)]
    rounding = abs(prod) * math.fsum(abs(w) * math.ulp(float(tk)) / 2 for w, tk in zip(weights, t5))
    with np.errstate(over="ignore"):
        unscaled = np.ldexp(coef, -e * np.arange(4))  # t[z2_0..z2_k] = t[x_0..x_k] 2^(-e k)
        fourth = float(np.ldexp(five[-1], -4 * e))
    return InverseInterpolation(z2, t, unscaled, float(value), (float(fifth[0]), float(fifth[1])), fourth, error, rounding)
