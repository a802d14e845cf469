"""Problem 5: the period integral (1) by the 3-point Gauss-Legendre rule (11), composite.

Rule (11) on ``[a, b]``, ``m = (a+b)/2``, ``mu = (b-a)/2``::

    Q(f) = (b-a)/18 [5 f(m - sqrt(3/5) mu) + 8 f(m) + 5 f(m + sqrt(3/5) mu)]

is the 3-point Gauss-Legendre rule: nodes ``0, +-sqrt(3/5)`` and weights ``8/9, 5/9`` on
``[-1, 1]`` (``(b-a)/18 = mu/9``), exact for polynomials of degree 5 ([1]_ section 4.7).
:data:`GAUSS3` holds it as data and checks itself on construction. :func:`composite`
sums it over ``n`` equal subintervals (``S_n``, 5(c)) in chunks of vectorised numpy work,
so ``n = 10^7`` runs in a few megabytes.

The period integral (1), ``T = 4 sqrt(l/(2g)) int_0^alpha dtheta / sqrt(cos theta - cos alpha)``,
has an integrand that is infinite at ``theta = alpha`` (like ``(alpha - theta)^(-1/2)``):

* 5(a): the closed trapezoidal and Simpson rules evaluate the integrand at both ends,
  ``theta = alpha`` included, where it is infinite: they cannot be applied as they stand.
  The open Gauss rule (11) never touches the ends.
* Its error is not ``O(h^6)`` but ``O(h^(1/2))``: the last subinterval alone holds
  ``int_{alpha-h}^alpha ~ 2 sqrt(h) / sqrt(sin alpha)``, which a polynomial rule misses
  by a fixed fraction; so ``S_n`` converges like ``n^(-1/2)`` ([2]_).
* The substitution ``sin(theta/2) = sin(alpha/2) sin(phi)`` turns (1) into
  ``T = 4 sqrt(l/g) int_0^(pi/2) dphi / sqrt(1 - k^2 sin^2 phi)``, ``k = sin(alpha/2)``
  (the complete elliptic integral ``K(k)``), whose integrand is analytic: the same rule
  then converges like ``h^6`` and faster.

References
----------
.. [1] R. L. Burden, J. D. Faires, *Numerical Analysis*, 9th ed., Brooks/Cole, 2011,
   section 4.7 (Gaussian quadrature) and 4.9 (improper integrals).
.. [2] P. J. Davis, P. Rabinowitz, *Methods of Numerical Integration*, 2nd ed., Academic
   Press, 1984, chapter 2 (integrands with end-point singularities).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from . import _validate as v
from .cases import G
from .errors import InputError
from .results import Result

#: Subintervals evaluated per vectorised chunk: 3 * 2^16 doubles per array, ~1.5 MB.
CHUNK = 1 << 16
#: The largest n accepted (about 3 s of numpy work per 10^7).
MAX_N = 10**9


@dataclass(frozen=True)
class Rule:
    """An interpolatory quadrature rule on ``[-1, 1]`` that checks itself.

    Attributes
    ----------
    name : str
    nodes, weights : tuple of float
        On ``[-1, 1]``; ``Q(f) = mu sum_i w_i f(m + mu x_i)`` on ``[a, b]``.
    degree : int
        The claimed degree of exactness; checked on construction: exact (to rounding) on
        ``1, x, ..., x^degree`` and not on ``x^(degree+1)``, weights summing to 2.
    """

    name: str
    nodes: tuple[float, ...]
    weights: tuple[float, ...]
    degree: int

    def __post_init__(self):
        x = np.array(self.nodes, dtype=float)
        w = np.array(self.weights, dtype=float)
        if x.shape != w.shape or x.ndim != 1 or not np.all(np.abs(x) <= 1):
            raise ValueError(f"rule {self.name}: nodes and weights must match, nodes in [-1, 1]")
        if abs(w.sum() - 2) > 8 * np.finfo(float).eps:
            raise ValueError(f"rule {self.name}: weights sum to {w.sum()!r}, not 2 (= length of [-1, 1])")
        for k in range(self.degree + 2):
            exact = 2 / (k + 1) if k % 2 == 0 else 0.0  # int_{-1}^{1} x^k dx
            err = abs(float(w @ x**k) - exact)
            ok = err <= 16 * np.finfo(float).eps
            if k <= self.degree and not ok:
                raise ValueError(f"rule {self.name}: not exact for x^{k} (error {err:.3e})")
            if k == self.degree + 1 and ok:
                raise ValueError(f"rule {self.name}: exact for x^{k}: degree is more than {self.degree}")

    def apply(self, f: Callable[[np.ndarray], np.ndarray], a: float, b: float) -> float:
        """One application on ``[a, b]`` (5(b))."""
        return composite(self, f, a, b, 1)


#: Rule (11): 3-point Gauss-Legendre, degree of exactness 5.
GAUSS3 = Rule(
    "Gauss-Legendre 3-point, rule (11)",
    nodes=(-math.sqrt(3 / 5), 0.0, math.sqrt(3 / 5)),
    weights=(float(Fraction(5, 9)), float(Fraction(8, 9)), float(Fraction(5, 9))),
    degree=5,
)


def composite(rule: Rule, f: Callable[[np.ndarray], np.ndarray], a: float, b: float, n: int,
              chunk: int = CHUNK) -> float:
    """``S_n = sum_{i=1}^n Q_i``: ``rule`` on each of ``n`` equal subintervals of ``[a, b]`` (5(c)).

    Processed ``chunk`` subintervals at a time: memory stays ``O(chunk)`` whatever ``n``.
    Each chunk is summed by numpy's pairwise summation and the chunk sums by
    ``math.fsum``, so the summation error stays near ``u log(n)`` relative.

    Parameters
    ----------
    rule : Rule
    f : callable
        Vectorised integrand, called on arrays of shape ``(k, len(rule.nodes))``.
    a, b : float
        The interval (``a < b``).
    n : int
        Number of subintervals, ``>= 1``.
    """
    a, b = v.finite("a", a), v.finite("b", b)
    if not a < b:
        raise InputError("b", b, f"> a = {a!r}")
    n = v.integer("n", n, 1, MAX_N)
    chunk = v.integer("chunk", chunk, 1)
    h = (b - a) / n
    mu = 0.5 * h
    x = np.asarray(rule.nodes, dtype=float)
    w = np.asarray(rule.weights, dtype=float)
    sums = []
    for i0 in range(0, n, chunk):
        i = np.arange(i0, min(i0 + chunk, n), dtype=float)
        mid = a + (i + 0.5) * h  # m_i, computed directly: no drift from repeated addition
        vals = np.asarray(f(mid[:, None] + mu * x[None, :]), dtype=float)
        sums.append(float(np.sum(vals @ w)))
    return mu * math.fsum(sums)


# --------------------------------------------------------------------------- integral (1)
def period_integrand(alpha: float) -> Callable[[np.ndarray], np.ndarray]:
    """``1/sqrt(cos theta - cos alpha)``, the integrand of (1).

    Evaluated as ``1/sqrt(2 sin((alpha+theta)/2) sin((alpha-theta)/2))`` (the identity
    ``cos x - cos y = -2 sin((x+y)/2) sin((x-y)/2)``): ``alpha - theta`` is exact for
    ``theta`` near ``alpha`` (Sterbenz), so no digits cancel near the singularity.
    """
    def f(theta):
        return 1.0 / np.sqrt(2.0 * np.sin(0.5 * (alpha + theta)) * np.sin(0.5 * (alpha - theta)))

    return f


def substituted_integrand(alpha: float) -> Callable[[np.ndarray], np.ndarray]:
    """``sqrt(2) / sqrt(1 - k^2 sin^2 phi)``, ``k = sin(alpha/2)``: (1)'s integrand after
    ``sin(theta/2) = k sin(phi)``, on ``phi in [0, pi/2]`` (module docstring)."""
    k = math.sin(0.5 * alpha)

    def f(phi):
        s = k * np.sin(phi)
        return math.sqrt(2.0) / np.sqrt((1.0 - s) * (1.0 + s))

    return f


def period_prefactor(length: float, g: float) -> float:
    """``4 sqrt(l/(2g))``, the factor in front of the integral in (1)."""
    return 4 * math.sqrt(length / (2 * g))


def quadrature_period(length, amplitude, n: int, g=G, substitution: bool = False, rule: Rule = GAUSS3) -> float:
    """The period (1) with the integral replaced by ``S_n`` (rule (11) on ``n`` subintervals).

    ``substitution=True`` integrates the substituted, regular form over ``[0, pi/2]``.
    """
    length = v.positive("length", length)
    alpha = v.amplitude("amplitude", amplitude)
    g = v.positive("g", g)
    n = v.integer("n", n, 1, MAX_N)
    if alpha == 0:
        return 2 * math.pi * math.sqrt(length / g)  # the limit of (1) as alpha -> 0
    if substitution:
        s = composite(rule, substituted_integrand(alpha), 0.0, 0.5 * math.pi, n)
    else:
        s = composite(rule, period_integrand(alpha), 0.0, alpha, n)
    return period_prefactor(length, g) * s


@dataclass(frozen=True, eq=False)
class QuadratureRow(Result):
    """One row of the 5(d) table.

    Attributes
    ----------
    n : int
    period, error : float
        ``S_n``-based period of (1) and ``|period - exact|``.
    rate : float or None
        Observed order ``log(e_prev/e)/log(n/n_prev)`` against the previous row (None
        for the first, or when either error is at the rounding level).
    substitution_period, substitution_error, substitution_rate : float or None
        The same with the substitution (None when not asked for).
    """

    n: int
    period: float
    error: float
    rate: float | None
    substitution_period: float | None = None
    substitution_error: float | None = None
    substitution_rate: float | None = None


def observed_rates(ns, errors, floor: float) -> list[float | None]:
    """``log(e_{i-1}/e_i) / log(n_i/n_{i-1})``, None where an error is at or below ``floor``."""
    out: list[float | None] = [None]
    for (n0, e0), (n1, e1) in zip(zip(ns, errors), zip(ns[1:], errors[1:])):
        ok = e0 > floor and e1 > floor and n0 != n1
        out.append(math.log(e0 / e1) / math.log(n1 / n0) if ok else None)
    return out


def convergence_table(length, amplitude, ns, exact: float, g=G, substitution: bool = False) -> list[QuadratureRow]:
    """The table of 5(d): ``n``, period, ``|error|`` against ``exact`` and observed rate."""
    ns = [v.integer("n", n, 1, MAX_N) for n in ns]
    if not ns:
        raise InputError("n", "[]", "at least one number of subintervals")
    floor = 64 * np.finfo(float).eps * abs(exact)  # below this an error is rounding, not truncation
    periods = [quadrature_period(length, amplitude, n, g) for n in ns]
    errors = [abs(p - exact) for p in periods]
    rates = observed_rates(ns, errors, floor)
    sp: list[float | None]
    se: list[float | None]
    sr: list[float | None]
    if substitution:
        sub_periods = [quadrature_period(length, amplitude, n, g, substitution=True) for n in ns]
        sub_errors = [abs(p - exact) for p in sub_periods]
        sp, se, sr = list(sub_periods), list(sub_errors), observed_rates(ns, sub_errors, floor)
    else:
        sp = se = sr = [None] * len(ns)
    return [QuadratureRow(*row) for row in zip(ns, periods, errors, rates, sp, se, sr)]


#: 5(a), in words.
ANSWER_5A = (
    "No. The trapezoidal and Simpson rules are closed: they evaluate the integrand at both "
    "ends of [0, alpha], and at theta = alpha it is 1/sqrt(cos(alpha) - cos(alpha)) = 1/0, "
    "infinite. They cannot be applied to (1) as it stands (only after removing the singularity, "
    "e.g. by the substitution sin(theta/2) = sin(alpha/2) sin(phi)). Rule (11) is open (Gauss "
    "nodes lie inside the interval), so it can be applied, but the singularity limits its "
    "convergence to O(n^(-1/2))."
)
