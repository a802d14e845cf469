"""The period of the simple pendulum: small-angle, AGM (7)-(8), and to any number of digits.

The exact period of a pendulum of length ``l`` released at rest from amplitude
``alpha`` is ``T = 2 pi sqrt(l/g) / M(1, cos(alpha/2))`` with ``M`` the
arithmetic-geometric mean, equations (7)-(8) of the coursework.

References
----------
.. [1] C. G. Carvalhaes, P. Suppes, "Approximations for the period of the simple
   pendulum based on the arithmetic-geometric mean", Am. J. Phys. 76, 1150-1154 (2008).
.. [2] NIST DLMF 19.8.5: K(k) = pi / (2 M(1, sqrt(1 - k^2))).
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from . import _validate as v
from .cases import G_EXACT, G
from .exact import Exact

#: Upper bound on AGM iterations: from b0 = 1e-300 the AGM converges in 17.
_MAX_ITERATIONS = 64
# Stop when a - b <= 4 eps a: the next step would change v by less than eps^2.
_RTOL = 4 * np.finfo(float).eps


def small_angle_period(length: Any, g: Any = G) -> Any:
    """Small-angle period ``2 pi sqrt(l/g)`` (problem 1). Vectorised over ``length``."""
    if np.ndim(length) == 0:
        return 2 * math.pi * math.sqrt(v.positive("length", length) / v.positive("g", g))
    lengths = np.asarray(length, dtype=float)
    if not np.all(np.isfinite(lengths) & (lengths > 0)):
        bad = lengths[~(np.isfinite(lengths) & (lengths > 0))][0]
        v.positive("length", bad)
    return 2 * np.pi * np.sqrt(lengths / v.positive("g", g))


def agm_mean(b0: Any, iterations: int | None = None) -> Any:
    """The AGM value ``v`` of (7)-(8) started from ``(a0, b0) = (1, b0)``.

    Parameters
    ----------
    b0 : float or array_like, 0 < b0 <= 1
        ``cos(alpha/2)``.
    iterations : int, optional
        ``None`` iterates to convergence in double precision; ``7`` is the coursework's
        fixed count: ``v = (a7 + b7)/2``.

    Returns
    -------
    float or ndarray
        ``(a_n + b_n)/2`` after ``n`` iterations of (7).
    """
    if np.ndim(b0) == 0:
        a, b = 1.0, float(b0)
        if iterations is None:
            for _ in range(_MAX_ITERATIONS):
                if a - b <= _RTOL * a:
                    break
                a, b = 0.5 * (a + b), math.sqrt(a * b)
        else:
            for _ in range(iterations):
                a, b = 0.5 * (a + b), math.sqrt(a * b)
        return 0.5 * (a + b)
    bs = np.array(b0, dtype=float)
    as_ = np.ones_like(bs)
    if iterations is None:
        for _ in range(_MAX_ITERATIONS):
            if np.all(as_ - bs <= _RTOL * as_):
                break
            as_, bs = 0.5 * (as_ + bs), np.sqrt(as_ * bs)
    else:
        for _ in range(iterations):
            as_, bs = 0.5 * (as_ + bs), np.sqrt(as_ * bs)
    return 0.5 * (as_ + bs)


def _check_amplitudes(amplitude: Any) -> Any:
    if np.ndim(amplitude) == 0:
        return v.amplitude("amplitude", amplitude)
    alpha = np.asarray(amplitude, dtype=float)
    ok = np.isfinite(alpha) & (alpha >= 0) & (alpha < np.pi)
    if not np.all(ok):
        v.amplitude("amplitude", alpha[~ok][0])
    return alpha


def agm_period(length: Any, amplitude: Any, g: Any = G, iterations: int | None = None) -> Any:
    """Exact period by the arithmetic-geometric mean, equations (7)-(8).

    Parameters
    ----------
    length : float or array_like
        Pendulum length ``l`` > 0, m.
    amplitude : float or array_like
        Release angle ``alpha`` in ``[0, pi)``, rad. Broadcast against ``length``.
    g : float
        Gravitational acceleration, m/s^2.
    iterations : int, optional
        ``None`` (default): iterate (7) to convergence, accurate to about 1e-16 relative
        for every amplitude up to ``pi - 1e-12`` and beyond. ``7``: the coursework's
        ``T^`` bit for bit, exact only while ``alpha`` is not too close to ``pi`` (see
        :func:`fixed_iterations_limit`).

    Returns
    -------
    float or ndarray
        ``T^ = 2 pi sqrt(l/g) / v`` (8).

    Notes
    -----
    ``b0 = cos(alpha/2)`` is computed directly: near ``alpha = pi`` it is small but has
    full relative accuracy, and the AGM is multiplicatively well conditioned, so no
    digits are lost there (unlike ``scipy.special.ellipk(sin(alpha/2)**2)``, whose
    argument ``m`` rounds to 1).
    """
    if iterations is not None:
        iterations = v.integer("iterations", iterations, 0, 1000)
    alpha = _check_amplitudes(amplitude)
    t0 = small_angle_period(length, g)
    if np.ndim(alpha) == 0 and np.ndim(t0) == 0:
        return t0 / agm_mean(math.cos(0.5 * alpha), iterations)
    # Arrays: one compiled pass, cos and the AGM fused, on all cores.
    from ._kernels import agm_means

    alpha = np.asarray(alpha, dtype=float)
    flat = np.ascontiguousarray(alpha).ravel()
    means = agm_means(flat, -1 if iterations is None else iterations, _RTOL).reshape(alpha.shape)
    return t0 / means


def agm_iterations(amplitude: float) -> int:
    """How many iterations of (7) double precision needs at ``amplitude`` (to convergence)."""
    a, b = 1.0, math.cos(0.5 * v.amplitude("amplitude", amplitude))
    for k in range(_MAX_ITERATIONS):
        if a - b <= _RTOL * a:
            return k
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return _MAX_ITERATIONS  # pragma: no cover - unreachable for b0 > 0


def period_mp(length: Any, amplitude: Any, g: Any = G_EXACT, dps: int = 50):
    """The period as an ``mpmath.mpf`` computed at ``dps`` digits of working precision.

    Inputs are taken exactly: a string is parsed as written (``"4pi/5"`` with the true
    pi), a float is its exact binary value. Uses ``mpmath.agm``, which is independent of
    this module's double-precision loop.
    """
    import mpmath

    from .exact import parse_angle, parse_number

    def exact(name, x, parser):
        return parser(name, x) if isinstance(x, str) else Exact.of(x)

    l_ = exact("length", length, parse_number)
    a_ = exact("amplitude", amplitude, parse_angle)
    g_ = exact("g", g, parse_number)
    v.positive("length", float(l_))
    v.positive("g", float(g_))
    with mpmath.workdps(dps):
        alpha = a_.mpf(dps)
        if not (0 <= alpha < mpmath.pi):
            v.amplitude("amplitude", a_.text or float(a_))
        t0 = 2 * mpmath.pi * mpmath.sqrt(l_.mpf(dps) / g_.mpf(dps))
        return t0 / mpmath.agm(1, mpmath.cos(alpha / 2))


def period_digits(length: Any, amplitude: Any, g: Any = G_EXACT, digits: int = 30) -> str:
    """The period to ``digits`` significant digits, every one of them right.

    Ziv's strategy: evaluate at two working precisions with growing guard digits until
    both round to the same ``digits``-digit decimal; that decimal is then correctly
    rounded unless the true value lies within 1e-(digits+guard) of a rounding boundary.
    """
    import mpmath

    digits = v.integer("digits", digits, 1, 100000)
    guard = 15
    while True:
        lo = mpmath.nstr(period_mp(length, amplitude, g, digits + guard), digits, strip_zeros=False)
        hi = mpmath.nstr(period_mp(length, amplitude, g, digits + 2 * guard), digits, strip_zeros=False)
        if lo == hi:
            return hi
        guard *= 2


def fixed_iterations_error(amplitude: Any, iterations: int = 7, dps: int = 60):
    """Relative truncation error ``v_n / M - 1`` of ``n`` iterations of (7), exactly.

    Computed in mpmath at ``dps`` digits, so it measures the truncation of the fixed
    iteration count alone, not rounding.
    """
    import mpmath

    with mpmath.workdps(dps):
        alpha = amplitude if isinstance(amplitude, mpmath.mpf) else Exact.of(amplitude).mpf(dps)
        b0 = mpmath.cos(alpha / 2)
        a, b = mpmath.mpf(1), b0
        for _ in range(iterations):
            a, b = (a + b) / 2, mpmath.sqrt(a * b)
        return (a + b) / 2 / mpmath.agm(1, b0) - 1


def fixed_iterations_limit(iterations: int = 7, rtol: float = 2.0**-53) -> float:
    """The largest amplitude at which ``iterations`` steps of (7) are exact in double precision.

    Returns the amplitude (rad) below which the truncation error of (8) after
    ``iterations`` steps is at most ``rtol`` (default: half an ulp, 1.1e-16); above it the
    fixed count ``T^`` is no longer the correctly rounded period. Found by bisection on
    ``log(pi - alpha)``; the truncation error grows monotonically with ``alpha``.
    """
    import mpmath

    lo, hi = -60.0, 1.0  # log(pi - alpha): hi is alpha = pi - e, error small
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        alpha = mpmath.pi - mpmath.e**mid
        if abs(fixed_iterations_error(alpha, iterations)) > rtol:
            lo = mid
        else:
            hi = mid
    return float(mpmath.pi - mpmath.e**hi)
