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
from typing import Any

import numpy as np

from ..core import validate as v
from ..core.cases import G
from ..core.errors import InputError
from .results import Result

#: Subintervals evaluated per vectorised chunk: 3 * 2^16 doubles per array, ~1.5 MB.
CHUNK = 1 << 16
#: The graded panels start with ``[0, k'/GRADED_FIRST]``: the integrand's singularities at
#: ``psi = +-i k'`` then lie 2 * GRADED_FIRST half-widths from that panel's centre.
GRADED_FIRST = 32
#: The largest n accepted: 1.4 s of numpy work on a quiet machine. More is of no use.
#: Against mpmath (``benchmarks/quadrature_cap.py``): the substituted integrand reaches the
#: rounding level by n = 100 at 4pi/5 and n = 1e5 at pi - 1e-3, and n = 1e7 still gives
#: 1.6e-12 at pi - 1e-6 (``graded=True`` reaches the rounding level with 3000 panels at
#: every double below pi); the plain integrand's error falls as n^(-1/2) without end in
#: reach (1.4e-4 at n = 1e6, 4.4e-5 at 1e7; full precision would need n ~ 1e31): each
#: further factor 10 buys half a digit for ten times the work, the rate long established.
MAX_N = 10**7
#: The most panels one convergence table evaluates, all its n together (the table
#: 1, 10, ..., 1e7 has 1.11e7).
MAX_TOTAL_N = 2 * MAX_N


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
            raise InputError("nodes", self.nodes, f"as many nodes as weights, all in [-1, 1] (rule {self.name})")
        if abs(w.sum() - 2) > 8 * np.finfo(float).eps:
            raise InputError("weights", self.weights,
                             f"weights that sum to 2, the length of [-1, 1]; these sum to {w.sum()!r} (rule {self.name})")
        for k in range(self.degree + 2):
            exact = 2 / (k + 1) if k % 2 == 0 else 0.0  # int_{-1}^{1} x^k dx
            err = abs(float(w @ x**k) - exact)
            ok = err <= 16 * np.finfo(float).eps
            if k <= self.degree and not ok:
                raise InputError("degree", self.degree,
                                 f"the rule's degree: it is not exact for x^{k} (error {err:.3e}, rule {self.name})")
            if k == self.degree + 1 and ok:
                raise InputError("degree", self.degree,
                                 f"the rule's degree: it is exact for x^{k}, so its degree is more than {self.degree} "
                                 f"(rule {self.name})")

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


def composite_graded(rule: Rule, f: Callable[[np.ndarray], np.ndarray], b: float, first: float, n: int,
                     chunk: int = CHUNK) -> float:
    """``rule`` on ``n`` panels of ``[0, b]`` graded geometrically towards 0.

    Panel edges ``0, e_1, ..., e_n = b`` with ``e_i = b r^(n-i)`` and ``e_1 = first``:
    each panel ``[e, r e]`` sees a singularity at distance about ``first`` from 0 under
    the same angle, so every panel converges alike however close the singularity is
    (geometric grading: Davis and Rabinowitz 1984, section 2.12; Schwab, *p- and hp-FEM*, 1998, section 3.3).
    """
    b = v.positive("b", b)
    first = v.positive("first", first)
    n = v.integer("n", n, 1, MAX_N)
    if n == 1 or first >= b:
        return composite(rule, f, 0.0, b, n, chunk)
    log_r = math.log(b / first) / (n - 1)
    x = np.asarray(rule.nodes, dtype=float)
    w = np.asarray(rule.weights, dtype=float)
    sums = [0.5 * first * float(np.asarray(f(0.5 * first * (1 + x)), dtype=float) @ w)]  # [0, e_1]
    for i0 in range(1, n, chunk):
        i = np.arange(i0, min(i0 + chunk, n), dtype=float)
        lo = b * np.exp(-(n - i) * log_r)  # e_i
        hi = b * np.exp(-(n - i - 1) * log_r)  # e_{i+1}
        mid, mu = 0.5 * (lo + hi), 0.5 * (hi - lo)
        vals = np.asarray(f(mid[:, None] + mu[:, None] * x[None, :]), dtype=float)
        sums.append(float(np.sum(mu * (vals @ w))))
    return math.fsum(sums)


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


def _sinc(y: np.ndarray) -> np.ndarray:
    """``sin(y)/y``, 1 at ``y = 0`` (an argument that underflowed)."""
    with np.errstate(invalid="ignore"):
        return np.where(y == 0, 1.0, np.sin(y) / np.where(y == 0, 1.0, y))


def scaled_period_integrand(alpha: float) -> Callable[[np.ndarray], np.ndarray]:
    """``alpha f(alpha (1 - d))``, :func:`period_integrand` on ``d = 1 - theta/alpha in [0, 1]``.

    With ``sin(alpha y/2) = (alpha y/2) sinc(alpha y/2)`` the factor ``alpha`` cancels::

        alpha f(alpha (1 - d)) = sqrt(2) / sqrt((2 - d) d sinc(alpha (2 - d)/2) sinc(alpha d/2))

    which is of order 1 for every amplitude, where ``2 sin sin ~ alpha^2`` underflows
    (at ``alpha = 1e-160`` it is subnormal, at ``1e-200`` zero). The variable ``d`` is
    the distance to the singularity itself, so a node near it carries a relative
    rounding of ``d``, not an absolute rounding of ``theta`` (which, relative to the
    distance ``alpha/(9n)`` of the last node, grows with ``n``).
    """
    def f(d):
        return math.sqrt(2.0) / np.sqrt((2.0 - d) * d * _sinc(0.5 * alpha * (2.0 - d)) * _sinc(0.5 * alpha * d))

    return f


def substituted_integrand(alpha: float, reflected: bool = False) -> Callable[[np.ndarray], np.ndarray]:
    """``sqrt(2) / sqrt(1 - k^2 sin^2 phi)``, ``k = sin(alpha/2)``: (1)'s integrand after
    ``sin(theta/2) = k sin(phi)``, on ``phi in [0, pi/2]`` (module docstring).

    ``1 - k^2 sin^2 phi`` is evaluated as ``k'^2 + k^2 cos^2 phi`` with
    ``k' = cos(alpha/2)`` computed from ``alpha`` directly: near ``alpha = pi``, ``k``
    rounds to 1 (once ``pi - alpha < 2e-8``) and ``1 - k^2 sin^2 phi`` would lose the
    ``k'^2`` that sets the integral. ``reflected=True`` gives the same integrand in
    ``psi = pi/2 - phi``, ``sqrt(2) / sqrt(k'^2 + k^2 sin^2 psi)``: its peak (width ``k'``)
    sits at ``psi = 0``, an exact end of the interval, where ``cos(phi)`` near ``pi/2``
    would carry the absolute rounding of ``phi`` (1e-16), comparable to ``k'`` near pi.
    """
    k, kp = math.sin(0.5 * alpha), math.cos(0.5 * alpha)

    def f(phi):
        c = k * np.cos(phi)
        return math.sqrt(2.0) / np.sqrt(kp * kp + c * c)

    def f_reflected(psi):
        s = k * np.sin(psi)
        return math.sqrt(2.0) / np.sqrt(kp * kp + s * s)

    return f_reflected if reflected else f


def period_prefactor(length: float, g: float) -> float:
    """``4 sqrt(l/(2g))``, the factor in front of the integral in (1).

    ``(l/2)/g`` equals ``l/(2g)`` bit for bit (halving is exact); :func:`validate.sqrt_ratio`
    keeps the root finite where the quotient overflows.
    """
    return 4 * v.sqrt_ratio(0.5 * length, g)


def quadrature_period(length, amplitude, n: int, g=G, substitution: bool = False, rule: Rule = GAUSS3,
                      graded: bool = False) -> float:
    """The period (1) with the integral replaced by ``S_n`` (rule (11) on ``n`` subintervals).

    ``S_n`` over ``[0, alpha]`` is computed as the same rule on ``[0, 1]`` applied to
    :func:`scaled_period_integrand` (the affine map ``theta = alpha (1 - d)`` carries the
    panels, nodes and weights over exactly: the same sum, mirrored), so that tiny amplitudes neither underflow nor
    lose digits. ``substitution=True`` integrates the substituted, regular form over
    ``[0, pi/2]`` (reflected, ``psi = pi/2 - phi``: the same panels mirrored, the same
    sum). Its peak has width ``k' = cos(alpha/2)``: equal panels need about ``n = 5/k'``
    for a relative error of 1e-12 (measured at ``pi - alpha = 1e-2`` and ``1e-3``), out of
    reach near pi (at ``pi - alpha = 1e-6``, ``n = 1e5`` still errs by 3.6e-2).
    ``graded=True`` grades the ``n`` panels geometrically towards the peak
    (:func:`composite_graded`, first panel ``[0, k'/32]``): ``n = 3000`` reaches the
    rounding level (2e-15 relative) at every amplitude up to the last double below pi:
    measured, by an adversarial search over amplitudes (``benchmarks/adversarial.py``,
    ``quadrature_search``; ``docs/accuracy.md``).
    """
    length, alpha, g = v.pendulum(length, amplitude, g)
    v.period_scale(length, g)  # refuses a period beyond the doubles, naming length or g
    n = v.integer("n", n, 1, MAX_N)
    if alpha == 0:
        return 2 * math.pi * math.sqrt(length / g)  # the limit of (1) as alpha -> 0
    if substitution:
        f = substituted_integrand(alpha, reflected=True)
        if graded:
            s = composite_graded(rule, f, 0.5 * math.pi, math.cos(0.5 * alpha) / GRADED_FIRST, n)
        else:
            s = composite(rule, f, 0.0, 0.5 * math.pi, n)
    else:
        if graded:
            raise InputError("graded", graded, "False without the substitution (the graded panels are for its peak)")
        s = composite(rule, scaled_period_integrand(alpha), 0.0, 1.0, n)
    return period_prefactor(length, g) * s


@dataclass(frozen=True, eq=False)
class QuadratureRow(Result):
    """One row of the 5(d) table.

    Attributes
    ----------
    n : int
    estimate, error : float
        ``S_n``-based estimate of the period (1) and ``|estimate - T^|``.
    rate : float or None
        Observed order ``log(e_prev/e)/log(n/n_prev)`` against the previous row (None
        for the first, or when either error is at the rounding level).
    substitution_estimate, substitution_error, substitution_rate : float or None
        The same with the substitution (None when not asked for).
    """

    n: int
    estimate: float
    error: float
    rate: float | None
    substitution_estimate: float | None = None
    substitution_error: float | None = None
    substitution_rate: float | None = None

    def to_dict(self) -> dict[str, Any]:
        """The fields; the substitution's three only where it was computed."""
        d = super().to_dict()
        if self.substitution_estimate is None:
            for k in ("substitution_estimate", "substitution_error", "substitution_rate"):
                del d[k]
        return d


def observed_rates(ns, errors, floor: float) -> list[float | None]:
    """``log(e_{i-1}/e_i) / log(n_i/n_{i-1})``, None where an error is at or below ``floor``."""
    out: list[float | None] = [None]
    for (n0, e0), (n1, e1) in zip(zip(ns, errors), zip(ns[1:], errors[1:])):
        ok = e0 > floor and e1 > floor and n0 != n1
        out.append(math.log(e0 / e1) / math.log(n1 / n0) if ok else None)
    return out


def convergence_table(length, amplitude, ns, reference: float, g=G, substitution: bool = False,
                      graded: bool = False, substitution_reference: float | None = None) -> list[QuadratureRow]:
    """The table of 5(d): ``n``, period, ``|error|`` against ``reference`` and observed rate.

    ``reference``: the period the errors are measured against (problem 5 passes ``t_hat``).
    ``graded`` (with ``substitution``): the substituted columns on graded panels
    (see :func:`quadrature_period`). ``substitution_reference``: the substituted columns'
    reference, when not ``reference`` (near pi, where ``T^`` of (8) is not the period).
    """
    if graded and not substitution:
        raise InputError("graded", graded, "False without the substitution (the graded panels are for its peak)")
    ns = [v.integer("n", n, 1, MAX_N) for n in ns]
    if not ns:
        raise InputError("n", "[]", "at least one number of subintervals")
    if sum(ns) > MAX_TOTAL_N:
        raise InputError("n", ns, f"numbers of subintervals summing to at most {MAX_TOTAL_N:.0e} (these sum to "
                                  f"{sum(ns):.3g})")
    floor = 64 * np.finfo(float).eps * abs(reference)  # below this an error is rounding, not truncation
    periods = [quadrature_period(length, amplitude, n, g) for n in ns]
    errors = [abs(p - reference) for p in periods]
    rates = observed_rates(ns, errors, floor)
    sp: list[float | None]
    se: list[float | None]
    sr: list[float | None]
    if substitution:
        sub_periods = [quadrature_period(length, amplitude, n, g, substitution=True, graded=graded) for n in ns]
        sub_reference = reference if substitution_reference is None else substitution_reference
        sub_errors = [abs(p - sub_reference) for p in sub_periods]
        sub_floor = 64 * np.finfo(float).eps * abs(sub_reference)
        sp, se, sr = list(sub_periods), list(sub_errors), observed_rates(ns, sub_errors, sub_floor)
    else:
        sp = se = sr = [None] * len(ns)
    return [QuadratureRow(*row) for row in zip(ns, periods, errors, rates, sp, se, sr)]
